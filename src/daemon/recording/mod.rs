//! Reading what recordings hold, for the commands that summarise them.

pub mod launches;
