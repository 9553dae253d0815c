//! Parameter identification (not yet implemented; see issue 5).
