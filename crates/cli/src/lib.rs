//! Command-line front ends (not yet implemented; see issues 4 and 5).
