//! The paper authors' MATLAB v5 `.mat` files, read directly (the format is small).
//!
//! A v5 file is a 128-byte header (116 bytes of text, a version and the endian indicator
//! `IM`/`MI`) followed by tagged data elements: a tag gives the type and byte count (or, in
//! the small-element form, both in 4 bytes with up to 4 bytes of data), data is padded to 8
//! bytes, and `miCOMPRESSED` elements hold one zlib-compressed element. Variables are
//! `miMATRIX` elements: array flags (class), dimensions, name, then the data by class —
//! numeric arrays column-major, sparse arrays as row indices `ir`, column starts `jc` and
//! values, cell arrays as one `miMATRIX` per cell.
//!
//! The dataset's variables: `phiPositions`, a cell array with one N×3 position matrix per
//! frame (dense or sparse), and `Eb`, the E×2 border edges with 1-based vertex indices. The
//! sample is a mesh without faces whose border is the loop the edges form.
//!
//! Every count is checked against the bytes actually present before it is used, so a
//! corrupt file gives an error, not an allocation of what its header claims. Two budgets
//! cover the whole file, not one variable: the bytes inflated from `miCOMPRESSED`
//! elements ([`MAX_DECOMPRESSED`]), and the numbers produced, counted as f64 after
//! widening ([`MAX_WIDENED`]: one `miINT8` byte becomes 8) — checked before each
//! allocation. Format: MathWorks, "MAT-File Format" (Level 5 MAT-files).
//!
//! ```
//! use close_io::formats::mat::parse_sample;
//! let err = parse_sample(b"MATLAB 7.3 MAT-file", "x.mat").unwrap_err().to_string();
//! assert!(err.contains("128-byte"));
//! ```

use std::io::Read;

use flate2::read::ZlibDecoder;

use std::cell::Cell;

use super::Sample;
use crate::error::{Error, Format, Result};
use crate::mesh::{MeshFrames, MAX_MESH_VERTICES};
use close_core::Error as CoreError;

/// Most bytes the compressed variables of one file may expand to, in all.
pub const MAX_DECOMPRESSED: u64 = 256 * 1024 * 1024;
/// Most bytes of f64 values (8 per number, sparse matrices counted dense) one file may
/// produce, in all variables.
pub const MAX_WIDENED: u64 = 128 * 1024 * 1024;
/// Most cells a sparse matrix may expand to when made dense.
const MAX_DENSE: usize = 3 * MAX_MESH_VERTICES;
/// Cell arrays nested deeper than this are refused (the dataset has one level).
const MAX_DEPTH: usize = 8;

const MI_INT8: u32 = 1;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_MATRIX: u32 = 14;
const MI_COMPRESSED: u32 = 15;
const MX_CELL: u32 = 1;
const MX_SPARSE: u32 = 5;

fn bad(message: impl ToString) -> Error {
    Error::parse(Format::Mat, message)
}

/// A variable's value, as far as the dataset needs.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// Dense real matrix, column-major (sparse ones are made dense).
    Matrix {
        dims: Vec<usize>,
        data: Vec<f64>,
    },
    Cell {
        dims: Vec<usize>,
        items: Vec<Value>,
    },
    /// A class the dataset does not use (struct, char, object, …), by MATLAB class number.
    Other(u32),
}

/// The tagged-element walk over a file: its byte order and what it has spent of the
/// file's budgets so far.
struct Walk {
    big: bool,
    inflated: Cell<u64>,
    widened: Cell<u64>,
}

/// One data element: type, its data, and where the next element starts.
struct Element<'a> {
    kind: u32,
    data: &'a [u8],
    next: usize,
}

impl Walk {
    fn new(big: bool) -> Walk {
        Walk { big, inflated: Cell::new(0), widened: Cell::new(0) }
    }

    /// Spend `values` numbers (8 bytes each as f64) of the file's budget, before allocating.
    fn widen(&self, values: usize) -> Result<()> {
        let total = self.widened.get().saturating_add((values as u64).saturating_mul(8));
        if total > MAX_WIDENED {
            return Err(CoreError::TooLarge {
                what: "bytes of numbers once widened to f64",
                got: Some(total),
                limit: MAX_WIDENED,
            }
            .into());
        }
        self.widened.set(total);
        Ok(())
    }

    /// Inflate one `miCOMPRESSED` element within what is left of the file's budget.
    fn inflate(&self, data: &[u8], pos: usize) -> Result<Vec<u8>> {
        let left = MAX_DECOMPRESSED - self.inflated.get();
        let mut inflated = Vec::new();
        ZlibDecoder::new(data)
            .take(left + 1)
            .read_to_end(&mut inflated)
            .map_err(|err| bad(format!("compressed variable at byte {pos}: {err}")))?;
        if inflated.len() as u64 > left {
            return Err(Error::over_limit("bytes decompressed", MAX_DECOMPRESSED as usize));
        }
        self.inflated.set(self.inflated.get() + inflated.len() as u64);
        Ok(inflated)
    }

    fn u32(&self, b: &[u8]) -> u32 {
        let a = [b[0], b[1], b[2], b[3]];
        if self.big {
            u32::from_be_bytes(a)
        } else {
            u32::from_le_bytes(a)
        }
    }

    fn element<'a>(&self, buf: &'a [u8], pos: usize) -> Result<Element<'a>> {
        let truncated = || bad(format!("truncated data element at byte {pos}"));
        let head = buf.get(pos..pos + 4).ok_or_else(truncated)?;
        let first = self.u32(head);
        if first >> 16 != 0 {
            // Small data element: count and type share the first 4 bytes.
            let n = (first >> 16) as usize;
            if n > 4 {
                return Err(bad(format!(
                    "small data element at byte {pos} claims {n} bytes (at most 4)"
                )));
            }
            let data = buf.get(pos + 4..pos + 4 + n).ok_or_else(truncated)?;
            return Ok(Element { kind: first & 0xffff, data, next: pos + 8 });
        }
        let n = self.u32(buf.get(pos + 4..pos + 8).ok_or_else(truncated)?) as usize;
        let start = pos + 8;
        let data = buf.get(start..start.checked_add(n).ok_or_else(truncated)?).ok_or_else(|| {
            bad(format!("data element at byte {pos} claims {n} bytes but only {} remain (truncated file?)", buf.len() - start.min(buf.len())))
        })?;
        let next = if first == MI_COMPRESSED { start + n } else { start + n.div_ceil(8) * 8 };
        Ok(Element { kind: first, data, next })
    }

    /// Numbers of any numeric data type, as f64.
    fn numbers(&self, kind: u32, b: &[u8]) -> Result<Vec<f64>> {
        let size = match kind {
            1 | 2 => 1,
            3 | 4 => 2,
            5..=7 => 4,
            9 | 12 | 13 => 8,
            other => return Err(bad(format!("data type {other} where numbers were expected"))),
        };
        if !b.len().is_multiple_of(size) {
            return Err(bad(format!(
                "{} bytes is not a whole number of {size}-byte values",
                b.len()
            )));
        }
        self.widen(b.len() / size)?;
        let word = |c: &[u8]| -> [u8; 8] {
            let mut w = [0u8; 8];
            if self.big {
                w[8 - c.len()..].copy_from_slice(c)
            } else {
                w[..c.len()].copy_from_slice(c)
            }
            w
        };
        let from =
            |w: [u8; 8]| if self.big { u64::from_be_bytes(w) } else { u64::from_le_bytes(w) };
        Ok(b.chunks_exact(size)
            .map(|c| {
                let v = from(word(c));
                match kind {
                    1 => v as u8 as i8 as f64,
                    2 => v as u8 as f64,
                    3 => v as u16 as i16 as f64,
                    4 => v as u16 as f64,
                    5 => v as u32 as i32 as f64,
                    6 => v as u32 as f64,
                    7 => f32::from_bits(v as u32) as f64,
                    9 => f64::from_bits(v),
                    12 => v as i64 as f64,
                    _ => v as f64,
                }
            })
            .collect())
    }

    /// Non-negative integers (dimensions, sparse indices).
    fn counts(&self, e: &Element, what: &str) -> Result<Vec<usize>> {
        self.numbers(e.kind, e.data)?
            .into_iter()
            .map(|v| {
                if v >= 0.0 && v.fract() == 0.0 && v < 1e15 {
                    Ok(v as usize)
                } else {
                    Err(bad(format!("{what} holds {v}")))
                }
            })
            .collect()
    }

    /// Every variable in `buf` (top level, or a decompressed element).
    fn variables(&self, buf: &[u8], out: &mut Vec<(String, Value)>, nested: bool) -> Result<()> {
        let mut pos = 0;
        while pos < buf.len() {
            let e = self.element(buf, pos)?;
            match e.kind {
                MI_MATRIX => out.push(self.matrix(e.data, 0)?),
                MI_COMPRESSED if !nested => {
                    let inflated = self.inflate(e.data, pos)?;
                    self.variables(&inflated, out, true)?;
                }
                other => {
                    return Err(bad(format!(
                        "unexpected data type {other} at byte {pos} (expected a variable)"
                    )))
                }
            }
            pos = e.next;
        }
        Ok(())
    }

    /// One `miMATRIX` body → its name and value.
    fn matrix(&self, body: &[u8], depth: usize) -> Result<(String, Value)> {
        if depth > MAX_DEPTH {
            return Err(bad(format!("cell arrays nested more than {MAX_DEPTH} deep")));
        }
        if body.is_empty() {
            // MATLAB writes an empty cell entry as a bare tag.
            return Ok((String::new(), Value::Matrix { dims: vec![0, 0], data: Vec::new() }));
        }
        let flags = self.element(body, 0)?;
        if flags.kind != MI_UINT32 || flags.data.len() != 8 {
            return Err(bad("a variable does not start with its array flags"));
        }
        let class = self.u32(flags.data) & 0xff;
        let complex = self.u32(flags.data) & 0x800 != 0;
        let dims_el = self.element(body, flags.next)?;
        if dims_el.kind != MI_INT32 {
            return Err(bad("a variable's dimensions are missing"));
        }
        let dims = self.counts(&dims_el, "a dimension")?;
        let name_el = self.element(body, dims_el.next)?;
        if name_el.kind != MI_INT8 && name_el.kind != 2 {
            return Err(bad("a variable's name is missing"));
        }
        let name = String::from_utf8_lossy(name_el.data).into_owned();
        let mut pos = name_el.next;
        let mut next = || -> Result<Element> {
            let e = self.element(body, pos)?;
            pos = e.next;
            Ok(e)
        };
        let total = dims
            .iter()
            .try_fold(1usize, |a, &d| a.checked_mul(d))
            .ok_or_else(|| bad(format!("{name}: dimensions {dims:?} overflow")))?;
        let value = match class {
            MX_CELL => {
                let mut items = Vec::new();
                for k in 0..total {
                    let e =
                        next().map_err(|err| bad(format!("{name}: cell {k} of {total}: {err}")))?;
                    if e.kind != MI_MATRIX {
                        return Err(bad(format!("{name}: cell {k} is not an array")));
                    }
                    items.push(self.matrix(e.data, depth + 1)?.1);
                }
                Value::Cell { dims, items }
            }
            MX_SPARSE => {
                let (ir, jc, pr) = (next()?, next()?, next()?);
                if complex {
                    return Err(bad(format!("{name} holds complex numbers")));
                }
                self.sparse(
                    &name,
                    dims,
                    self.counts(&ir, "a sparse row index")?,
                    self.counts(&jc, "a sparse column start")?,
                    self.numbers(pr.kind, pr.data)?,
                )?
            }
            6..=15 => {
                let real = next()?;
                if complex {
                    return Err(bad(format!("{name} holds complex numbers")));
                }
                let data = self.numbers(real.kind, real.data)?;
                if data.len() != total {
                    return Err(bad(format!(
                        "{name}: {dims:?} needs {total} values but {} are stored",
                        data.len()
                    )));
                }
                Value::Matrix { dims, data }
            }
            other => Value::Other(other),
        };
        Ok((name, value))
    }

    /// Expand compressed-column storage into a dense column-major matrix.
    fn sparse(
        &self,
        name: &str,
        dims: Vec<usize>,
        ir: Vec<usize>,
        jc: Vec<usize>,
        pr: Vec<f64>,
    ) -> Result<Value> {
        let [rows, cols] = dims[..] else {
            return Err(bad(format!("{name}: a sparse array must be 2-D, not {dims:?}")));
        };
        let cells = rows.saturating_mul(cols);
        if cells > MAX_DENSE {
            return Err(Error::too_large(
                "cells of one sparse matrix made dense",
                cells,
                MAX_DENSE,
            ));
        }
        self.widen(cells)?;
        let corrupt = |why: &str| bad(format!("{name}: corrupt sparse array ({why})"));
        if jc.len() != cols + 1 || jc.windows(2).any(|w| w[0] > w[1]) {
            return Err(corrupt("column starts"));
        }
        let nnz = jc[cols];
        if nnz > ir.len() || nnz > pr.len() {
            return Err(corrupt("fewer values than column starts announce"));
        }
        let mut data = vec![0.0; cells];
        for c in 0..cols {
            for (&r, &value) in ir[jc[c]..jc[c + 1]].iter().zip(&pr[jc[c]..jc[c + 1]]) {
                if r >= rows {
                    return Err(corrupt("row index out of range"));
                }
                data[c * rows + r] = value;
            }
        }
        Ok(Value::Matrix { dims, data })
    }
}

/// All variables of a MATLAB v5 file.
pub fn variables(bytes: &[u8]) -> Result<Vec<(String, Value)>> {
    if bytes.len() < 128 {
        return Err(bad(format!(
            "{} bytes is shorter than the 128-byte MAT-file header",
            bytes.len()
        )));
    }
    let text = String::from_utf8_lossy(&bytes[..116]);
    if text.starts_with("MATLAB 7.3") {
        return Err(bad("MATLAB v7.3 files (HDF5) are not supported: save with -v7 or -v6"));
    }
    let big = match &bytes[126..128] {
        b"IM" => false,
        b"MI" => true,
        _ => return Err(bad("not a MATLAB v5 .mat file (no IM/MI endian indicator at byte 126)")),
    };
    if !text.starts_with("MATLAB") {
        return Err(bad("not a MATLAB v5 .mat file (the header does not start with \"MATLAB\")"));
    }
    let mut out = Vec::new();
    Walk::new(big).variables(&bytes[128..], &mut out, false)?;
    Ok(out)
}

/// A matrix's rows as points: N×3 (or 3×N) → N points.
fn positions(value: &Value, what: &str) -> Result<Vec<[f64; 3]>> {
    let Value::Matrix { dims, data } = value else {
        return Err(bad(format!("{what} is not a numeric matrix")));
    };
    match dims[..] {
        [rows, 3] => Ok((0..rows).map(|r| [data[r], data[rows + r], data[2 * rows + r]]).collect()),
        [3, cols] => {
            Ok((0..cols).map(|c| [data[3 * c], data[3 * c + 1], data[3 * c + 2]]).collect())
        }
        _ => Err(bad(format!("{what} is {dims:?}, expected N×3 positions"))),
    }
}

/// `Eb`: E×2 (or 2×E) 1-based vertex pairs → 0-based edges.
fn edges(value: &Value) -> Result<Vec<[usize; 2]>> {
    let Value::Matrix { dims, data } = value else {
        return Err(bad("Eb is not a numeric matrix"));
    };
    let pairs: Vec<[f64; 2]> = match dims[..] {
        [rows, 2] => (0..rows).map(|r| [data[r], data[rows + r]]).collect(),
        [2, cols] => (0..cols).map(|c| [data[2 * c], data[2 * c + 1]]).collect(),
        _ => return Err(bad(format!("Eb is {dims:?}, expected E×2 vertex pairs"))),
    };
    pairs
        .into_iter()
        .map(|p| {
            p.map(|v| {
                if v >= 1.0 && v.fract() == 0.0 && v <= MAX_MESH_VERTICES as f64 {
                    Ok(v as usize - 1)
                } else {
                    Err(bad(format!("Eb holds {v}, not a 1-based vertex index")))
                }
            })
        })
        .map(|[a, b]| Ok([a?, b?]))
        .collect()
}

/// Read the dataset's `phiPositions` and `Eb` into a mesh sample named `name`.
pub fn parse_sample(bytes: &[u8], name: &str) -> Result<Sample> {
    let vars = variables(bytes)?;
    let find = |want: &str| {
        vars.iter().find(|(n, _)| n == want).map(|(_, v)| v).ok_or_else(|| {
            // Names that are words are the format's own; others are not quoted.
            let found: Vec<&str> = vars
                .iter()
                .map(|(n, _)| super::identifier(n).unwrap_or("(not a name)"))
                .take(16)
                .collect();
            bad(format!(
                "no variable {want:?} (the file holds {} variables: {}); expected phiPositions and Eb",
                vars.len(),
                found.join(", ")
            ))
        })
    };
    let frames = match find("phiPositions")? {
        Value::Cell { items, .. } if !items.is_empty() => items
            .iter()
            .enumerate()
            .map(|(k, m)| positions(m, &format!("phiPositions{{{}}}", k + 1)))
            .collect::<Result<Vec<_>>>()?,
        Value::Cell { .. } => {
            return Err(CoreError::Empty { what: "phiPositions is an empty cell array" }.into())
        }
        _ => return Err(bad("phiPositions is not a cell array (one N×3 matrix per frame)")),
    };
    let border_edges = edges(find("Eb")?)?;
    let stem = name.strip_suffix(".mat").unwrap_or(name);
    Ok(Sample {
        name: stem.to_string(),
        category: "upload".into(),
        frames: Vec::new(),
        mesh: Some(MeshFrames { faces: Vec::new(), frames, border_edges }),
        truth: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(endian: &[u8; 2]) -> Vec<u8> {
        let mut h = b"MATLAB 5.0 MAT-file, test".to_vec();
        h.resize(124, b' ');
        h.extend([0, 1]);
        h.extend(endian);
        h
    }

    /// A tagged element, little endian, padded.
    fn el(kind: u32, data: &[u8]) -> Vec<u8> {
        let mut v = kind.to_le_bytes().to_vec();
        v.extend((data.len() as u32).to_le_bytes());
        v.extend(data);
        v.resize(8 + data.len().div_ceil(8) * 8, 0);
        v
    }

    fn double_matrix(name: &str, rows: i32, cols: i32, values: &[f64]) -> Vec<u8> {
        let mut body = el(MI_UINT32, &[6, 0, 0, 0, 0, 0, 0, 0]);
        body.extend(el(MI_INT32, &[rows.to_le_bytes(), cols.to_le_bytes()].concat()));
        body.extend(el(MI_INT8, name.as_bytes()));
        body.extend(el(9, &values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<_>>()));
        el(MI_MATRIX, &body)
    }

    #[test]
    fn reads_a_hand_made_matrix_and_names_missing_variables() {
        let mut file = header(b"IM");
        file.extend(double_matrix("Eb", 2, 2, &[1.0, 2.0, 2.0, 3.0]));
        let vars = variables(&file).unwrap();
        assert_eq!(vars[0].0, "Eb");
        assert_eq!(edges(&vars[0].1).unwrap(), vec![[0, 1], [1, 2]]);
        assert!(parse_sample(&file, "x.mat").unwrap_err().to_string().contains("phiPositions"));
    }

    #[test]
    fn corrupt_files_are_named() {
        assert!(variables(&header(b"XX")).unwrap_err().to_string().contains("endian"));
        let mut file = header(b"IM");
        file.extend(double_matrix("Eb", 2, 2, &[1.0, 2.0, 2.0, 3.0]));
        file.truncate(file.len() - 12);
        assert!(variables(&file).unwrap_err().to_string().contains("truncated"));
        let mut file = header(b"IM");
        file.extend(double_matrix("Eb", 3, 2, &[1.0, 2.0, 2.0, 3.0]));
        assert!(variables(&file).unwrap_err().to_string().contains("needs 6 values"));
        let mut file = header(b"IM");
        file.extend(el(MI_COMPRESSED, b"not zlib"));
        assert!(variables(&file).unwrap_err().to_string().contains("compressed"));
        let mut file = header(b"IM");
        file.extend(double_matrix("Eb", 2, 2, &[0.0, 2.0, 2.5, 3.0]));
        let vars = variables(&file).unwrap();
        assert!(edges(&vars[0].1).unwrap_err().to_string().contains("1-based"));
    }

    #[test]
    fn sparse_arrays_expand_and_bad_ones_are_refused() {
        let e = Walk::new(false);
        let m = e.sparse("s", vec![2, 2], vec![1, 0], vec![0, 1, 2], vec![5.0, 7.0]).unwrap();
        assert_eq!(m, Value::Matrix { dims: vec![2, 2], data: vec![0.0, 5.0, 7.0, 0.0] });
        assert!(e.sparse("s", vec![2, 2], vec![3, 0], vec![0, 1, 2], vec![5.0, 7.0]).is_err());
        assert!(e.sparse("s", vec![2, 2], vec![1], vec![0, 1, 2], vec![5.0]).is_err());
        assert!(matches!(
            e.sparse("s", vec![1 << 40, 1 << 30], vec![], vec![], vec![]),
            Err(Error::Core(CoreError::TooLarge { .. }))
        ));
    }
}
