//! Figure data: what a figure shows, as numbers and labels; the front end draws it (the CLI
//! writes SVG and PNG of these, for the study's figures and its own commands' plots alike).

/// A figure and the stem of its files (`figure4` → `figure4.svg`, `figure4.png`).
#[derive(Debug, Clone)]
pub struct Figure {
    /// File stem.
    pub stem: String,
    /// What it shows.
    pub kind: FigureKind,
}

/// The kinds of figure.
#[derive(Debug, Clone)]
pub enum FigureKind {
    /// Deformed shapes `y(x)` on axes of equal scale.
    Shapes(ShapesFigure),
    /// Tip positions against time.
    History(HistoryFigure),
    /// Stacked panels of line series.
    Lines(LinesFigure),
}

/// Deformed shapes of several models.
#[derive(Debug, Clone)]
pub struct ShapesFigure {
    /// Title.
    pub title: String,
    /// Span (m): the undeformed beam is drawn from 0 to `length`.
    pub length: f64,
    /// The models, each solid or dashed.
    pub models: Vec<ModelShapes>,
    /// Colour the entries along a dark-to-light gradient (in order) instead of the line colours
    /// (snapshots in time).
    pub gradient: bool,
}

/// The shapes of one model (or reference).
#[derive(Debug, Clone)]
pub struct ModelShapes {
    /// Legend text.
    pub label: String,
    /// Whether its curves are dashed.
    pub dashed: bool,
    /// One polyline of node positions `(x, y)` (m) per shape.
    pub shapes: Vec<Vec<(f64, f64)>>,
}

/// Tip histories of several models.
#[derive(Debug, Clone)]
pub struct HistoryFigure {
    /// Title.
    pub title: String,
    /// End of the time axis (s).
    pub end_time: f64,
    /// Whether to draw the twist panel.
    pub has_torsion: bool,
    /// One series per model.
    pub series: Vec<TipSeries>,
}

/// The tip history of one model.
#[derive(Debug, Clone)]
pub struct TipSeries {
    /// Legend text.
    pub label: String,
    /// Whether its curves are dashed.
    pub dashed: bool,
    /// Times (s).
    pub t: Vec<f64>,
    /// Tip x (m).
    pub x: Vec<f64>,
    /// Tip y (m).
    pub y: Vec<f64>,
    /// Tip twist (rad), drawn with `has_torsion`.
    pub twist: Vec<f64>,
}

/// Stacked panels sharing a title.
#[derive(Debug, Clone)]
pub struct LinesFigure {
    /// Title.
    pub title: String,
    /// Panels, top to bottom.
    pub panels: Vec<Panel>,
}

/// One panel of a [`LinesFigure`].
#[derive(Debug, Clone)]
pub struct Panel {
    /// Horizontal axis label.
    pub x_label: String,
    /// Vertical axis label.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
}

/// One line of a [`Panel`].
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Whether it is dashed.
    pub dashed: bool,
    /// Index into the line colours; `None`: the series' position in its panel.
    pub colour: Option<usize>,
    /// Points `(x, y)`; non-finite ones are skipped.
    pub points: Vec<(f64, f64)>,
}
