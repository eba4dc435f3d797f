//! Dictionary-encoded string columns: a polars `Enum` over categories of the
//! table's own, in first-seen order.
//!
//! A column that repeats a few strings over many rows (a trace's file path
//! and section) is stored as one small integer per row and each string once.
//! Parquet then writes the dictionary as it stands instead of hashing every
//! row's string to discover it (`docs/speed.md`, "The traces table"). The
//! categories belong to the table, never to the process-global
//! `Categorical` mapping, whose dictionary would hold every string the
//! process ever saw in an order that depends on the threads.

use std::collections::HashMap;

use polars::prelude::{
    with_match_categorical_physical_type, CatNative, Categorical16Type, Categorical32Type,
    Categorical8Type, CategoricalChunked, CategoricalPhysical, ChunkedArray, Column, DataType,
    FrozenCategories, IntoSeries, PolarsCategoricalType,
};
use polars_arrow::array::PrimitiveArray;
use polars_arrow::bitmap::{Bitmap, MutableBitmap};

use super::table_err;
use crate::error::{Error, Result};

/// A column as runs of category codes (null or not) over its categories.
#[derive(Default)]
pub(super) struct CodeRuns {
    categories: Vec<String>,
    index: HashMap<String, u32>,
    runs: Vec<(Option<u32>, usize)>,
}

impl CodeRuns {
    /// Appends `n` rows of `value`, adding it to the categories when new:
    /// one lookup per run, none per row.
    pub(super) fn push(&mut self, value: Option<&str>, n: usize) {
        let code = value.map(|s| self.code(s));
        self.push_code(code, n);
    }

    /// Appends a dictionary column's rows: its codes are read as runs and
    /// each distinct code is looked up in its dictionary once, so joining
    /// tables never turns a row back into a string.
    pub(super) fn extend(&mut self, column: &Column) -> Result<()> {
        let series = column.as_materialized_series();
        let (DataType::Enum(_, mapping) | DataType::Categorical(_, mapping)) = series.dtype()
        else {
            return Err(Error::Table(format!(
                "column '{}' is {}, not a dictionary",
                series.name(),
                series.dtype()
            )));
        };
        let codes = series
            .to_physical_repr()
            .cast(&DataType::UInt32)
            .map_err(table_err)?;
        let mut runs: Vec<(Option<u32>, usize)> = Vec::new();
        for array in codes.u32().map_err(table_err)?.downcast_iter() {
            for code in array.iter().map(|c| c.copied()) {
                match runs.last_mut() {
                    Some((c, n)) if *c == code => *n += 1,
                    _ => runs.push((code, 1)),
                }
            }
        }
        // An unknown code reads as null, as polars' own checked constructor has it.
        let mut remap: HashMap<u32, Option<u32>> = HashMap::new();
        for (code, n) in runs {
            let code = code.and_then(|c| {
                *remap
                    .entry(c)
                    .or_insert_with(|| mapping.cat_to_str(c).map(|s| self.code(s)))
            });
            self.push_code(code, n);
        }
        Ok(())
    }

    /// The code of `s`, a new one when `s` is not yet a category.
    fn code(&mut self, s: &str) -> u32 {
        if let Some(&c) = self.index.get(s) {
            return c;
        }
        let c = self.categories.len() as u32;
        self.categories.push(s.to_string());
        self.index.insert(s.to_string(), c);
        c
    }

    fn push_code(&mut self, code: Option<u32>, n: usize) {
        match self.runs.last_mut() {
            Some((last, m)) if *last == code => *m += n,
            _ => self.runs.push((code, n)),
        }
    }

    /// The column: an `Enum` over the categories in first-seen order, with
    /// the smallest code type that holds them.
    pub(super) fn into_column(self, name: &str) -> Result<Column> {
        let frozen =
            FrozenCategories::new(self.categories.iter().map(String::as_str)).map_err(table_err)?;
        let physical = frozen.physical();
        let dtype = DataType::from_frozen_categories(frozen);
        let series = with_match_categorical_physical_type!(physical, |$C| {
            enum_series::<$C>(name, dtype, &self.runs).into_series()
        });
        Ok(series.into())
    }
}

/// The codes of `runs` as `T`'s integers under `dtype`.
fn enum_series<T: PolarsCategoricalType>(
    name: &str,
    dtype: DataType,
    runs: &[(Option<u32>, usize)],
) -> CategoricalChunked<T> {
    let total = runs.iter().map(|r| r.1).sum();
    let mut codes: Vec<T::Native> = Vec::with_capacity(total);
    let mut valid = MutableBitmap::with_capacity(total);
    for &(code, n) in runs {
        codes.extend(std::iter::repeat_n(
            T::Native::from_cat(code.unwrap_or(0)),
            n,
        ));
        valid.extend_constant(n, code.is_some());
    }
    let valid: Bitmap = valid.into();
    let valid = (valid.unset_bits() > 0).then_some(valid);
    let array = PrimitiveArray::from_vec(codes).with_validity(valid);
    let codes = ChunkedArray::<T::PolarsPhysical>::with_chunk(name.into(), array);
    // SAFETY: every code was handed out by `CodeRuns::push` as an index into
    // the categories `dtype` was frozen from, and `T` is the physical type
    // `FrozenCategories` chose for their number.
    unsafe { CategoricalChunked::<T>::from_cats_and_dtype_unchecked(codes, dtype) }
}

/// Whether a column is dictionary-encoded (ours, or one read from a file
/// another tool wrote).
pub(super) fn is_dictionary(dtype: &DataType) -> bool {
    matches!(dtype, DataType::Enum(..) | DataType::Categorical(..))
}
