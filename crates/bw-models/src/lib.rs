//! Bouc-Wen collision models (work in progress).
