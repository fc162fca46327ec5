//! Error measures of a drawing against the exact one.
