//! The FMI 2.0 co-simulation C functions (FMI 2.0 §2.1 and §4.2: `fmi2Functions.h`): the one
//! module of the crate with `unsafe` (raw pointers from the host in, C strings out). Each
//! function turns its pointers into slices and strings, checks them (null pointers are errors),
//! and calls the safe [`Instance`] inside `catch_unwind`: no panic crosses into the host (a
//! caught one puts the instance in the error state and is logged). Functions of capabilities the
//! FMU does not declare (FMU state, directional derivatives, input derivatives, asynchronous
//! steps) return `fmi2Error` with a logged message.

#![allow(unsafe_code)]

use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::instance::{Instance, Status};

type Component = *mut c_void;
type Environment = *mut c_void;
type ValueReference = c_uint;
type Boolean = c_int;
type Logger =
    unsafe extern "C" fn(Environment, *const c_char, c_int, *const c_char, *const c_char, ...);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct CallbackFunctions {
    logger: Option<Logger>,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(Environment, c_int)>,
    component_environment: Environment,
}

/// `fmi2CoSimulation`.
const CO_SIMULATION: c_int = 1;
/// `fmi2Error`.
const ERROR: c_int = Status::Error as c_int;
/// Marks a live [`Slave`] (a pointer the host passes that is not one is refused).
const MAGIC: u64 = 0x666c_6578_7769_6e67;

/// What `fmi2Instantiate` hands out.
struct Slave {
    magic: u64,
    instance: Instance,
    /// The strings of the last fmi2GetString, alive until the next call.
    strings: Vec<CString>,
}

/// `text` as a C string (interior NULs replaced).
fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', " ")).unwrap_or_default()
}

/// The text of a caught panic.
fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    p.downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".to_string())
}

/// A C string argument, or `None` if null or not UTF-8.
///
/// # Safety
/// `p` is null or a NUL-terminated string alive for the call.
unsafe fn text<'a>(p: *const c_char) -> Option<&'a str> {
    if p.is_null() {
        None
    } else {
        // SAFETY: as the function's contract.
        unsafe { CStr::from_ptr(p) }.to_str().ok()
    }
}

/// An array argument of `n` elements, or `None` if null with `n > 0`.
///
/// # Safety
/// `p` is null or points to `n` elements alive for the call.
unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    if n == 0 {
        Some(&[])
    } else if p.is_null() {
        None
    } else {
        // SAFETY: as the function's contract.
        Some(unsafe { std::slice::from_raw_parts(p, n) })
    }
}

/// A mutable array argument of `n` elements, or `None` if null with `n > 0`.
///
/// # Safety
/// `p` is null or points to `n` writable elements alive for the call.
unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Option<&'a mut [T]> {
    if n == 0 {
        Some(&mut [])
    } else if p.is_null() {
        None
    } else {
        // SAFETY: as the function's contract.
        Some(unsafe { std::slice::from_raw_parts_mut(p, n) })
    }
}

/// Run `f` on the slave behind `c` with panics caught; `fmi2Error` for a null or foreign
/// pointer.
fn with(c: Component, function: &str, f: impl FnOnce(&mut Slave) -> Status) -> c_int {
    if c.is_null() {
        return ERROR;
    }
    // SAFETY: FMI 2.0 §2.1.5: the host passes back the pointer fmi2Instantiate returned, until
    // fmi2FreeInstance, and calls one function of an instance at a time. The magic number
    // refuses a pointer that was never one of ours.
    let slave = unsafe { &mut *c.cast::<Slave>() };
    if slave.magic != MAGIC {
        return ERROR;
    }
    match catch_unwind(AssertUnwindSafe(|| f(slave))) {
        Ok(s) => s as c_int,
        Err(p) => {
            let text = panic_text(&*p);
            catch_unwind(AssertUnwindSafe(|| slave.instance.fail(function, &text)))
                .map_or(Status::Fatal as c_int, |s| s as c_int)
        }
    }
}

/// The error of a null array argument.
fn null(slave: &mut Slave, function: &str, what: &str) -> Status {
    slave
        .instance
        .error(function, &format!("{what} is a null pointer"))
}

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// # Safety
/// FMI 2.0 §2.1.5: the strings are NUL-terminated or null, `functions` null or valid.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resource_location: *const c_char,
    functions: *const CallbackFunctions,
    _visible: Boolean,
    logging_on: Boolean,
) -> Component {
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: as the function's contract.
        let name = unsafe { text(instance_name) }
            .unwrap_or("flexwing")
            .to_string();
        // SAFETY: as the function's contract.
        let (logger, env) = match unsafe { functions.as_ref() } {
            Some(f) => (f.logger, f.component_environment),
            None => (None, std::ptr::null_mut()),
        };
        let c_name = c_string(&name);
        let log = Box::new(move |status: Status, category: &str, message: &str| {
            if let Some(logger) = logger {
                let category = c_string(category);
                // The message is the format string (no arguments): a `%` of ours is doubled.
                let message = c_string(&message.replace('%', "%%"));
                // SAFETY: the host's logger, with the environment it gave and C strings alive
                // for the call.
                unsafe {
                    logger(
                        env,
                        c_name.as_ptr(),
                        status as c_int,
                        category.as_ptr(),
                        message.as_ptr(),
                    );
                }
            }
        });
        if fmu_type != CO_SIMULATION {
            log(
                Status::Error,
                "logStatusError",
                "fmi2Instantiate: this FMU is for co-simulation only (fmuType fmi2CoSimulation)",
            );
            return std::ptr::null_mut();
        }
        // SAFETY: as the function's contract.
        let (Some(guid), Some(location)) =
            (unsafe { text(guid) }, unsafe { text(resource_location) })
        else {
            log(
                Status::Error,
                "logStatusError",
                "fmi2Instantiate: fmuGUID or fmuResourceLocation is null or not UTF-8",
            );
            return std::ptr::null_mut();
        };
        match Instance::new(guid, location, logging_on != 0, log) {
            Ok(instance) => Box::into_raw(Box::new(Slave {
                magic: MAGIC,
                instance,
                strings: Vec::new(),
            }))
            .cast::<c_void>(),
            Err(_) => std::ptr::null_mut(),
        }
    }));
    result.unwrap_or(std::ptr::null_mut())
}

/// # Safety
/// `c` is null or a pointer fmi2Instantiate returned, not yet freed.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: Component) {
    if c.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: as the function's contract: the box fmi2Instantiate made.
        let mut slave = unsafe { Box::from_raw(c.cast::<Slave>()) };
        if slave.magic == MAGIC {
            slave.magic = 0;
            drop(slave);
        } else {
            // Not ours: leave it.
            std::mem::forget(slave);
        }
    }));
}

/// # Safety
/// As every instance function: `c` from fmi2Instantiate.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Component,
    logging_on: Boolean,
    _n_categories: usize,
    _categories: *const *const c_char,
) -> c_int {
    with(c, "fmi2SetDebugLogging", |s| {
        s.instance.set_debug_logging(logging_on != 0)
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Component,
    tolerance_defined: Boolean,
    tolerance: f64,
    start_time: f64,
    stop_time_defined: Boolean,
    stop_time: f64,
) -> c_int {
    with(c, "fmi2SetupExperiment", |s| {
        s.instance.setup_experiment(
            (tolerance_defined != 0).then_some(tolerance),
            start_time,
            (stop_time_defined != 0).then_some(stop_time),
        )
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Component) -> c_int {
    with(c, "fmi2EnterInitializationMode", |s| {
        s.instance.enter_initialization()
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Component) -> c_int {
    with(c, "fmi2ExitInitializationMode", |s| {
        s.instance.exit_initialization()
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: Component) -> c_int {
    with(c, "fmi2Terminate", |s| s.instance.terminate())
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: Component) -> c_int {
    with(c, "fmi2Reset", |s| s.instance.reset())
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut f64,
) -> c_int {
    let f = "fmi2GetReal";
    with(c, f, |s| {
        // SAFETY: as the function's contract.
        match unsafe { (slice(vr, nvr), slice_mut(value, nvr)) } {
            (Some(vr), Some(value)) => s.instance.get_real(vr, value),
            _ => null(s, f, "vr or value"),
        }
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *const f64,
) -> c_int {
    let f = "fmi2SetReal";
    with(c, f, |s| {
        // SAFETY: as the function's contract.
        match unsafe { (slice(vr, nvr), slice(value, nvr)) } {
            (Some(vr), Some(value)) => s.instance.set_real(vr, value),
            _ => null(s, f, "vr or value"),
        }
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    _value: *mut c_int,
) -> c_int {
    let f = "fmi2GetInteger";
    with(c, f, |s| match unsafe { slice(vr, nvr) } {
        Some(vr) => s.instance.no_variables(f, "Integer", vr),
        None => null(s, f, "vr"),
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    _value: *const c_int,
) -> c_int {
    let f = "fmi2SetInteger";
    with(c, f, |s| match unsafe { slice(vr, nvr) } {
        Some(vr) => s.instance.no_variables(f, "Integer", vr),
        None => null(s, f, "vr"),
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    _value: *mut Boolean,
) -> c_int {
    let f = "fmi2GetBoolean";
    with(c, f, |s| match unsafe { slice(vr, nvr) } {
        Some(vr) => s.instance.no_variables(f, "Boolean", vr),
        None => null(s, f, "vr"),
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    _value: *const Boolean,
) -> c_int {
    let f = "fmi2SetBoolean";
    with(c, f, |s| match unsafe { slice(vr, nvr) } {
        Some(vr) => s.instance.no_variables(f, "Boolean", vr),
        None => null(s, f, "vr"),
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements. The strings returned live
/// until the next call of this function on the instance.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut *const c_char,
) -> c_int {
    let f = "fmi2GetString";
    with(c, f, |s| {
        // SAFETY: as the function's contract.
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice_mut(value, nvr) })
        else {
            return null(s, f, "vr or value");
        };
        match s.instance.get_string(vr) {
            Ok(texts) => {
                s.strings = texts.into_iter().map(c_string).collect();
                for (v, t) in value.iter_mut().zip(&s.strings) {
                    *v = t.as_ptr();
                }
                Status::Ok
            }
            Err(status) => status,
        }
    })
}

/// # Safety
/// As every instance function; `vr` and `value` hold `nvr` elements (C strings or null).
#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *const *const c_char,
) -> c_int {
    let f = "fmi2SetString";
    with(c, f, |s| {
        // SAFETY: as the function's contract.
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice(value, nvr) })
        else {
            return null(s, f, "vr or value");
        };
        // SAFETY: each element a C string or null, as the function's contract.
        let texts: Vec<Option<&str>> = value.iter().map(|&p| unsafe { text(p) }).collect();
        s.instance.set_string(vr, &texts)
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: Component,
    current_communication_point: f64,
    communication_step_size: f64,
    _no_set_fmu_state_prior_to_current_point: Boolean,
) -> c_int {
    with(c, "fmi2DoStep", |s| {
        s.instance
            .do_step(current_communication_point, communication_step_size)
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: Component) -> c_int {
    with(c, "fmi2CancelStep", |s| {
        s.instance.error(
            "fmi2CancelStep",
            "no step is pending: fmi2DoStep runs synchronously (canRunAsynchronuously = false)",
        )
    })
}

/// # Safety
/// As every instance function; `value` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: Component, _kind: c_int, _value: *mut c_int) -> c_int {
    with(c, "fmi2GetStatus", |s| {
        s.instance.error(
            "fmi2GetStatus",
            "fmi2DoStepStatus and fmi2PendingStatus exist only for asynchronous steps \
             (canRunAsynchronuously = false)",
        )
    })
}

/// `fmi2LastSuccessfulTime`.
const LAST_SUCCESSFUL_TIME: c_int = 2;
/// `fmi2Terminated`.
const TERMINATED: c_int = 3;

/// # Safety
/// As every instance function; `value` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Component, kind: c_int, value: *mut f64) -> c_int {
    let f = "fmi2GetRealStatus";
    with(c, f, |s| {
        // SAFETY: as the function's contract.
        let Some(value) = (unsafe { slice_mut(value, 1) }) else {
            return null(s, f, "value");
        };
        if kind == LAST_SUCCESSFUL_TIME {
            value[0] = s.instance.time();
            Status::Ok
        } else {
            s.instance.error(
                f,
                &format!("status kind {kind}: only fmi2LastSuccessfulTime (2) is a Real status"),
            )
        }
    })
}

/// # Safety
/// As every instance function; `value` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: Component,
    kind: c_int,
    _value: *mut c_int,
) -> c_int {
    let f = "fmi2GetIntegerStatus";
    with(c, f, |s| {
        s.instance.error(
            f,
            &format!("status kind {kind}: FMI 2.0 has no Integer status"),
        )
    })
}

/// # Safety
/// As every instance function; `value` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: Component,
    kind: c_int,
    value: *mut Boolean,
) -> c_int {
    let f = "fmi2GetBooleanStatus";
    with(c, f, |s| {
        // SAFETY: as the function's contract.
        let Some(value) = (unsafe { slice_mut(value, 1) }) else {
            return null(s, f, "value");
        };
        if kind == TERMINATED {
            value[0] = Boolean::from(s.instance.terminated());
            Status::Ok
        } else {
            s.instance.error(
                f,
                &format!("status kind {kind}: only fmi2Terminated (3) is a Boolean status"),
            )
        }
    })
}

/// # Safety
/// As every instance function; `value` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: Component,
    kind: c_int,
    _value: *mut *const c_char,
) -> c_int {
    let f = "fmi2GetStringStatus";
    with(c, f, |s| {
        s.instance.error(
            f,
            &format!("status kind {kind}: fmi2PendingStatus exists only for asynchronous steps"),
        )
    })
}

/// The error of a capability the model description does not declare.
fn unsupported(c: Component, function: &str, capability: &str) -> c_int {
    with(c, function, |s| {
        s.instance.error(
            function,
            &format!("not supported: the FMU declares {capability} = false"),
        )
    })
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: Component, _state: *mut *mut c_void) -> c_int {
    unsupported(c, "fmi2GetFMUstate", "canGetAndSetFMUstate")
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: Component, _state: *mut c_void) -> c_int {
    unsupported(c, "fmi2SetFMUstate", "canGetAndSetFMUstate")
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Component, _state: *mut *mut c_void) -> c_int {
    unsupported(c, "fmi2FreeFMUstate", "canGetAndSetFMUstate")
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: Component,
    _state: *mut c_void,
    _size: *mut usize,
) -> c_int {
    unsupported(c, "fmi2SerializedFMUstateSize", "canSerializeFMUstate")
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Component,
    _state: *mut c_void,
    _bytes: *mut c_char,
    _size: usize,
) -> c_int {
    unsupported(c, "fmi2SerializeFMUstate", "canSerializeFMUstate")
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Component,
    _bytes: *const c_char,
    _size: usize,
    _state: *mut *mut c_void,
) -> c_int {
    unsupported(c, "fmi2DeSerializeFMUstate", "canSerializeFMUstate")
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: Component,
    _unknown: *const ValueReference,
    _n_unknown: usize,
    _known: *const ValueReference,
    _n_known: usize,
    _dv_known: *const f64,
    _dv_unknown: *mut f64,
) -> c_int {
    unsupported(
        c,
        "fmi2GetDirectionalDerivative",
        "providesDirectionalDerivative",
    )
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: Component,
    _vr: *const ValueReference,
    _nvr: usize,
    _order: *const c_int,
    _value: *const f64,
) -> c_int {
    unsupported(
        c,
        "fmi2SetRealInputDerivatives",
        "canInterpolateInputs (the hold parameter chooses zero or linear)",
    )
}

/// # Safety
/// As every instance function.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: Component,
    _vr: *const ValueReference,
    _nvr: usize,
    _order: *const c_int,
    _value: *mut f64,
) -> c_int {
    unsupported(
        c,
        "fmi2GetRealOutputDerivatives",
        "maxOutputDerivativeOrder > 0",
    )
}
