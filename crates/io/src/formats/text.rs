//! Plain text / CSV borders: one vertex per line, `x,y,z` or `x y z` (tabs and `;` too).
//! Blank lines and lines starting with `#` are skipped; one header line of words is allowed.
//! At most one border's vertices (and a closing repeat of vertex 0) are read.
//!
//! ```
//! use close_io::formats::text::parse_frame;
//! let frame = parse_frame("x,y,z\n0,0,0\n1 0 0\n1,1,0\n# a comment\n0,1,0\n").unwrap();
//! assert_eq!(frame.len(), 4);
//! assert!(parse_frame("0,0,0\n1,zero,0\n").unwrap_err().to_string().contains("line 2"));
//! ```

use super::MAX_FILE_BYTES;
use crate::error::{Error, Format, Result};
use close_core::border::MAX_VERTICES;
use close_core::Error as CoreError;

/// Parse one frame of vertices.
pub fn parse_frame(text: &str) -> Result<Vec<[f64; 3]>> {
    if text.len() > MAX_FILE_BYTES {
        return Err(Error::too_large("bytes of text", text.len(), MAX_FILE_BYTES));
    }
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let numbers: Vec<f64> =
            match fields.iter().map(|f| f.parse::<f64>()).collect::<Result<_, _>>() {
                Ok(numbers) => numbers,
                // A header line of words before any vertex.
                Err(_)
                    if out.is_empty()
                        && fields.iter().all(|f| f.chars().all(char::is_alphabetic)) =>
                {
                    continue
                }
                Err(_) => {
                    // Where, not what: an error never quotes the file.
                    let field = fields.iter().position(|f| f.parse::<f64>().is_err()).unwrap_or(0);
                    return Err(Error::parse_at(
                        Format::Text,
                        k + 1,
                        format!(
                            "field {} of {} is not a number (expected x,y,z)",
                            field + 1,
                            fields.len()
                        ),
                    ));
                }
            };
        if numbers.len() != 3 {
            return Err(Error::parse_at(
                Format::Text,
                k + 1,
                format!("expected x,y,z but found {} values", numbers.len()),
            ));
        }
        // One more than a border's vertices: a closing vertex may repeat vertex 0.
        if out.len() > MAX_VERTICES {
            return Err(Error::over_limit("vertices in one frame", MAX_VERTICES + 1));
        }
        out.push([numbers[0], numbers[1], numbers[2]]);
    }
    if out.is_empty() {
        return Err(CoreError::Empty { what: "the text file holds no vertex" }.into());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_lines_are_named() {
        assert!(matches!(parse_frame(""), Err(Error::Core(CoreError::Empty { .. }))));
        assert!(matches!(
            parse_frame(&"0 0 0\n".repeat(MAX_VERTICES + 2)),
            Err(Error::Core(CoreError::TooLarge { .. }))
        ));
        assert!(parse_frame("1,2\n").unwrap_err().to_string().contains("line 1"));
        assert!(parse_frame("0 0 0\n1 2 3 4\n").unwrap_err().to_string().contains("4 values"));
        // NaN parses as a number here; the border check names it.
        assert!(parse_frame("nan,0,0\n").unwrap()[0][0].is_nan());
    }
}
