//! The sheet names steptable's workbooks share: the reader looks for them,
//! the template workbook and the output workbook write them. A leaf module,
//! so that the output side names a sheet without knowing the reader.

/// The sheet name of the published method's table.
pub const TABLE_SHEET: &str = "SEQUENTIAL CONTROL DESCRIPTION";
/// The sheet name of the engineer's settings, when a workbook has one.
pub const SETTINGS_SHEET: &str = "SETTINGS";
/// The sheet name of the signals pinned to the wiring's addresses.
pub const ADDRESSES_SHEET: &str = "ADDRESSES";
