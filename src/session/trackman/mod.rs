//! TrackMan's formats: its CSV export out and in (`csv`), its report JSON in (`report`), and what both
//! readers give beside the shots, the rows' labels and the rows left out (`rows`).

pub mod csv;
pub mod report;
pub mod rows;
