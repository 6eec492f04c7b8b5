//! The sheet names steptable's workbooks share: the reader looks for them,
//! the template workbook and the output workbook write them. A leaf module,
//! so that the output side names a sheet without knowing the reader. The
//! labels of the SETTINGS sheet's rows stand beside its name.

/// The sheet name of the published method's table.
pub const TABLE_SHEET: &str = "SEQUENTIAL CONTROL DESCRIPTION";
/// The sheet name of the engineer's settings, when a workbook has one.
pub const SETTINGS_SHEET: &str = "SETTINGS";
/// The sheet name of the signals pinned to the wiring's addresses.
pub const ADDRESSES_SHEET: &str = "ADDRESSES";

/// The labels of the SETTINGS sheet's rows, as written there.
pub const SETTING_LABELS: [&str; 17] = [
    "target",
    "board",
    "on stop",
    "on estop",
    "on halt",
    "hold-safe",
    "de-energise on halt",
    "start permissive",
    "interlock",
    "hold on estop",
    "mnemonic",
    "scan time",
    "safety",
    "modes",
    "home order",
    "designations",
    "supervision",
];
