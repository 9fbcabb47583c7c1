//! CSV with a header from the field names (the `csv` crate, serde), every non-finite number
//! written as an empty cell: no `inf` or `NaN` ever reaches a result file.

use std::io;

/// The CSV bytes of `rows` (header from the field names); a non-finite number (a state that
/// blew up) is an empty cell.
pub fn bytes<R: serde::Serialize>(rows: impl IntoIterator<Item = R>) -> io::Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for row in rows {
        w.serialize(row).map_err(io::Error::other)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| io::Error::other(e.error().to_string()))?;
    finite_cells(bytes)
}

/// `csv`, with every cell that reads as a non-finite number emptied.
fn finite_cells(csv: Vec<u8>) -> io::Result<Vec<u8>> {
    // Every non-finite cell contains "inf" or "NaN": without either anywhere (the rule), the
    // text is returned as it is, in one pass over the bytes instead of a parse that keeps every
    // record (2 million of them, 124 MB, for examples/long_chain.toml's nodes).
    if !csv.windows(3).any(|w| w == b"inf" || w == b"NaN") {
        return Ok(csv);
    }
    let non_finite = |c: &[u8]| matches!(c, b"inf" | b"-inf" | b"NaN" | b"+inf" | b"-NaN");
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(csv.as_slice());
    let mut records = Vec::new();
    let mut any = false;
    for record in r.byte_records() {
        let record = record.map_err(io::Error::other)?;
        any |= record.iter().any(non_finite);
        records.push(record);
    }
    if !any {
        return Ok(csv);
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    for record in &records {
        let cells: Vec<&[u8]> = record
            .iter()
            .map(|c| if non_finite(c) { &b""[..] } else { c })
            .collect();
        w.write_record(cells).map_err(io::Error::other)?;
    }
    w.into_inner()
        .map_err(|e| io::Error::other(e.error().to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_numbers_become_empty_cells() {
        #[derive(serde::Serialize)]
        struct Row {
            name: &'static str,
            a: f64,
            b: f64,
        }
        let mut w = csv::Writer::from_writer(Vec::new());
        for (name, a, b) in [("x", 1.5, f64::INFINITY), ("inf", f64::NAN, -f64::INFINITY)] {
            w.serialize(Row { name, a, b }).unwrap();
        }
        let text = finite_cells(w.into_inner().unwrap()).unwrap();
        // The label "inf" is text, but nothing tells it from the number: it goes too; labels
        // are model names, never "inf".
        assert_eq!(String::from_utf8(text).unwrap(), "name,a,b\nx,1.5,\n,,\n");
    }
}
