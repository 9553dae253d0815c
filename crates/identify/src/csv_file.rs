//! The CSV files measurements come in: `#` comment lines anywhere, one header line, fields
//! trimmed. Every error names the file and the 1-based line it is about.

use crate::error::IdentifyError;
use std::path::Path;

/// The text of the file at `path`.
///
/// # Errors
/// [`IdentifyError::Io`] where it cannot be read.
pub(crate) fn read(path: &Path) -> Result<String, IdentifyError> {
    std::fs::read_to_string(path).map_err(|source| IdentifyError::Io {
        path: path.to_owned(),
        source,
    })
}

/// [`IdentifyError::Data`] at `line` of `path`.
pub(crate) fn data_error(path: &Path, line: u64, message: String) -> IdentifyError {
    IdentifyError::Data {
        path: path.to_owned(),
        line,
        message,
    }
}

/// CSV text being read: its header, the header's line, and the records after it.
pub(crate) struct CsvText<'a> {
    path: &'a Path,
    reader: csv::Reader<&'a [u8]>,
    /// The column names.
    pub headers: csv::StringRecord,
    /// The header's 1-based line (after any comment and blank lines).
    pub header_line: u64,
    /// The 1-based line of each record.
    record_lines: Vec<u64>,
}

impl<'a> CsvText<'a> {
    /// Starts reading `text`, the contents of `path` (used in messages).
    ///
    /// # Errors
    /// [`IdentifyError::Data`] where the header cannot be read.
    pub fn new(path: &'a Path, text: &'a str) -> Result<Self, IdentifyError> {
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .from_reader(text.as_bytes());
        let header_line = text
            .lines()
            .position(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
            .map_or(1, |i| i as u64 + 1);
        let headers = reader
            .headers()
            .map_err(|e| data_error(path, header_line, e.to_string()))?
            .clone();
        // The csv reader's own line numbers skip the comment lines: the file's lines of the
        // records, in order, are the non-blank, non-comment lines after the header.
        let record_lines = text
            .lines()
            .enumerate()
            .skip(header_line as usize)
            .filter(|(_, l)| !l.trim_start().starts_with('#') && !l.trim().is_empty())
            .map(|(i, _)| i as u64 + 1)
            .collect();
        Ok(Self {
            path,
            reader,
            headers,
            header_line,
            record_lines,
        })
    }

    /// The position of column `name`, if the header has it.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.headers.iter().position(|h| h == name)
    }

    /// The column names.
    pub fn names(&self) -> Vec<&str> {
        self.headers.iter().collect()
    }

    /// [`IdentifyError::Data`] at `line` of this file.
    pub fn error(&self, line: u64, message: String) -> IdentifyError {
        data_error(self.path, line, message)
    }

    /// Each record after the header, read by `row` from the record and its line; the first
    /// error stops the reading.
    ///
    /// # Errors
    /// [`IdentifyError::Data`] at the line of a malformed record or of the first `Err` of
    /// `row`.
    pub fn rows<T>(
        &mut self,
        mut row: impl FnMut(&csv::StringRecord, u64) -> Result<T, String>,
    ) -> Result<Vec<T>, IdentifyError> {
        let mut out = Vec::new();
        let (path, lines) = (self.path, &self.record_lines);
        let line_of = |k: u64| lines.get(k as usize).copied().unwrap_or(0);
        for (k, record) in self.reader.records().enumerate() {
            let record = record.map_err(|e| {
                let k = e
                    .position()
                    .map_or(k as u64, |p| p.record().saturating_sub(1));
                data_error(path, line_of(k), e.to_string())
            })?;
            let line = line_of(k as u64);
            out.push(row(&record, line).map_err(|message| data_error(path, line, message))?);
        }
        Ok(out)
    }
}
