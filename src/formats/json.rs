//! Sample JSON, the canonical form (SPEC §2).
//!
//! ```
//! use close::formats::json::parse_sample;
//! let s = parse_sample(br#"{"name": "sq", "frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}"#).unwrap();
//! assert_eq!(s.frames[0].len(), 4);
//! assert!(parse_sample(b"{\"frames\": 3}").unwrap_err().to_string().contains("expected a sequence"));
//! ```

use super::{Sample, MAX_FILE_BYTES};
use crate::error::{Error, Result};

/// Parse a Sample JSON document. Errors name the line and column serde stopped at.
pub fn parse_sample(bytes: &[u8]) -> Result<Sample> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(Error::TooLarge(format!("{} bytes of JSON (at most {MAX_FILE_BYTES})", bytes.len())));
    }
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(Error::Empty("the JSON document is empty".into()));
    }
    let sample: Sample = serde_json::from_slice(bytes).map_err(|e| Error::parse("sample JSON", e))?;
    if sample.frames.is_empty() && sample.mesh.is_none() {
        return Err(Error::Empty("the sample has neither \"frames\" nor \"mesh\"".into()));
    }
    Ok(sample)
}

/// Write a sample as compact JSON.
pub fn to_json(sample: &Sample) -> String {
    serde_json::to_string(sample).expect("a sample always serialises")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn malformed_documents_are_named() {
        for (doc, what) in [
            (&b""[..], "empty"),
            (b"not json", "parse"),
            (b"{\"frames\": [[[0, 0]]]}", "parse"),
            (b"{\"name\": \"x\"}", "empty"),
            (b"{\"frames\": [[[0, 0, \"a\"]]]}", "parse"),
        ] {
            let err = parse_sample(doc).unwrap_err().to_string();
            assert!(err.contains(what) || err.to_lowercase().contains(what), "{err}");
        }
    }

    #[test]
    fn round_trip() {
        let s = Sample::from_frames("a", "napkin", vec![vec![[0.0, 1.0, 2.0]; 4]]);
        assert_eq!(parse_sample(to_json(&s).as_bytes()).unwrap(), s);
    }
}
