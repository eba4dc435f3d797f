//! Writing a table as Parquet: polars-parquet's file writer, driven here
//! rather than through polars' `ParquetWriter`, for two measured reasons
//! (`docs/speed.md`, "Writing Parquet"):
//!
//! - polars tries a dictionary on every float column: it hashes every
//!   value to estimate the cardinality (about 9 % of the CPU of a
//!   traces-on run), and where few values repeat, casts the column to a
//!   dictionary, a cast it does not support for floats, so it writes PLAIN
//!   whatever it found. Floats are written PLAIN here without the trial:
//!   the same bytes (the tests compare them with polars' own file).
//!   Integers, strings and dictionary (`cat`) columns keep polars' choice.
//! - polars encodes and compresses each row group's pages on the thread
//!   that writes them. Here every column chunk of a row group is encoded and
//!   compressed on rayon's threads, then written in column order, so the
//!   bytes are the same at any thread count.

use std::io::Write;

use polars::prelude::{CompatLevel, DataFrame, SchemaExt};
use polars_arrow::datatypes::{ArrowDataType, ArrowSchema, Metadata};
use polars_parquet::write::{
    array_to_columns, compress, fallible_streaming_iterator, get_dtype_encoding, to_parquet_schema,
    CompressedPage, CompressionOptions, DynIter, DynStreamingIterator, Encoding, FileWriter,
    KeyValue, StatisticsOptions, Version, WriteOptions,
};
use rayon::prelude::*;

use super::{table_err, Codec, Table, CODEC, ROW_GROUP_ROWS};
use crate::error::Result;

impl Table {
    /// Writes Parquet ([`CODEC`]) with file-level key-value metadata into `w`.
    pub fn write_parquet_to(&self, w: impl Write, metadata: &[(String, String)]) -> Result<()> {
        self.write_parquet_with(w, metadata, &[])
    }

    /// Writes Parquet ([`CODEC`], row groups of [`ROW_GROUP_ROWS`], column
    /// statistics) into `w`. The key-value pairs go into the Parquet footer
    /// and into the Arrow schema's metadata (what pyarrow's
    /// `schema.metadata`, polars and DuckDB show); `columns` gives each
    /// named column key-value pairs as Arrow field metadata (`unit`,
    /// `description`).
    pub fn write_parquet_with(
        &self,
        w: impl Write,
        metadata: &[(String, String)],
        columns: &[(String, Vec<(String, String)>)],
    ) -> Result<()> {
        self.write_parquet_codec(w, metadata, columns, CODEC)
    }

    /// As [`Table::write_parquet_with`] with another codec (the benchmark
    /// that chose [`CODEC`] uses it).
    pub fn write_parquet_codec(
        &self,
        w: impl Write,
        metadata: &[(String, String)],
        columns: &[(String, Vec<(String, String)>)],
        codec: Codec,
    ) -> Result<()> {
        let schema = arrow_schema(&self.df, columns);
        self.write_published(w, schema, metadata, codec)
    }

    /// As [`Table::write_parquet_with`], for one file of a dataset (a
    /// folder read as one table): dictionary columns are written without
    /// polars' `Enum` categories, which differ from file to file and which
    /// polars refuses to stack, so that readers join the files'
    /// dictionaries (polars reads them as `Categorical`, pyarrow as
    /// dictionaries, DuckDB as strings).
    pub fn write_parquet_open(
        &self,
        w: impl Write,
        metadata: &[(String, String)],
        columns: &[(String, Vec<(String, String)>)],
    ) -> Result<()> {
        let mut schema = arrow_schema(&self.df, columns);
        for field in schema.iter_values_mut() {
            if let ArrowDataType::Dictionary(key, values, _) = &field.dtype {
                field.dtype = ArrowDataType::Dictionary(*key, values.clone(), false);
            }
            if let Some(md) = field.metadata.as_deref() {
                let kept: Metadata = md
                    .iter()
                    .filter(|(k, _)| !k.as_str().starts_with("_PL_ENUM_VALUES"))
                    .map(|(k, v)| (k.clone(), v.clone()))
                    .collect();
                field.metadata = Some(std::sync::Arc::new(kept));
            }
        }
        self.write_published(w, schema, metadata, CODEC)
    }

    fn write_published(
        &self,
        w: impl Write,
        schema: ArrowSchema,
        metadata: &[(String, String)],
        codec: Codec,
    ) -> Result<()> {
        let mut kv = vec![arrow_schema_entry(&schema, metadata)];
        kv.extend(metadata.iter().cloned());
        let options = WriteOptions {
            statistics: StatisticsOptions::default(),
            version: Version::V1,
            compression: compression(codec),
            data_page_size: None,
        };
        write(&self.df, schema, w, options, kv)
    }

    /// Writes Parquet for tribo's own cache: uncompressed and without
    /// column statistics. Only tribo reads it back, whole; the codec and the
    /// min/max scans are what the published copy pays for its readers
    /// (`docs/speed.md`: the cache's copy of a large traces table).
    pub fn write_scratch_parquet(&self, w: impl Write) -> Result<()> {
        let schema = arrow_schema(&self.df, &[]);
        let kv = vec![arrow_schema_entry(&schema, &[])];
        let options = WriteOptions {
            statistics: StatisticsOptions::empty(),
            version: Version::V1,
            compression: CompressionOptions::Uncompressed,
            data_page_size: None,
        };
        write(&self.df, schema, w, options, kv)
    }
}

fn compression(codec: Codec) -> CompressionOptions {
    match codec {
        Codec::Uncompressed => CompressionOptions::Uncompressed,
        Codec::Snappy => CompressionOptions::Snappy,
        Codec::Lz4 => CompressionOptions::Lz4Raw,
        Codec::Zstd => CompressionOptions::Zstd(None),
    }
}

/// Writes `df` in row groups of [`ROW_GROUP_ROWS`]; each row group's
/// column chunks are encoded and compressed in parallel, then written in
/// order. `kv` is the footer's key-value metadata, as it is.
fn write(
    df: &DataFrame,
    schema: ArrowSchema,
    w: impl Write,
    options: WriteOptions,
    kv: Vec<(String, String)>,
) -> Result<()> {
    let mut df = df.clone();
    let df = polars::frame::chunk_df_for_writing(&mut df, ROW_GROUP_ROWS).map_err(table_err)?;
    let encodings: Vec<Vec<Encoding>> = schema.iter_values().map(|f| encoding(&f.dtype)).collect();
    let types = to_parquet_schema(&schema)
        .map_err(table_err)?
        .fields()
        .to_vec();
    let mut writer = FileWriter::try_new(w, schema, options).map_err(table_err)?;
    for batch in df.iter_chunks(CompatLevel::newest(), false) {
        if batch.is_empty() {
            continue;
        }
        let chunks: Vec<Vec<CompressedPage>> = batch
            .arrays()
            .par_iter()
            .zip(&types)
            .zip(&encodings)
            .map(|((array, t), e)| column_chunks(array.as_ref(), t, e, options))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect();
        let group = DynIter::new(chunks.iter().map(|pages| {
            Ok(DynStreamingIterator::new(
                fallible_streaming_iterator::convert(pages.iter().map(Ok)),
            ))
        }));
        writer.write(batch.len() as u64, group).map_err(table_err)?;
    }
    let kv = kv
        .into_iter()
        .map(|(key, value)| KeyValue {
            key,
            value: Some(value),
        })
        .collect();
    writer.end(Some(kv)).map_err(table_err)?;
    Ok(())
}

/// polars' encoding for a column, except PLAIN for floats (the module's
/// documentation says why).
fn encoding(dtype: &ArrowDataType) -> Vec<Encoding> {
    match dtype {
        ArrowDataType::Float32 | ArrowDataType::Float64 => vec![Encoding::Plain],
        _ => get_dtype_encoding(dtype),
    }
}

/// One array's column chunks (one per Parquet leaf), every page encoded
/// and compressed.
fn column_chunks(
    array: &dyn polars_arrow::array::Array,
    parquet_type: &polars_parquet::write::ParquetType,
    encoding: &[Encoding],
    options: WriteOptions,
) -> Result<Vec<Vec<CompressedPage>>> {
    let leaves =
        array_to_columns(array, parquet_type.clone(), options, encoding).map_err(table_err)?;
    leaves
        .into_iter()
        .map(|pages| {
            pages
                .map(|page| {
                    let page = page.map_err(table_err)?;
                    compress(page, Vec::new(), options.compression).map_err(table_err)
                })
                .collect()
        })
        .collect()
}

/// The Arrow schema of `df` as polars converts it, with `columns` as each
/// named field's metadata, added to what polars put there (an `Enum`'s
/// categories, which polars reads the dictionary column back by).
fn arrow_schema(df: &DataFrame, columns: &[(String, Vec<(String, String)>)]) -> ArrowSchema {
    let mut schema = df.schema().to_arrow(CompatLevel::newest());
    for (name, kv) in columns {
        if let Some(field) = schema.get_mut(name.as_str()) {
            let mut md = field.metadata.as_deref().cloned().unwrap_or_default();
            md.extend(pairs(kv));
            field.metadata = Some(std::sync::Arc::new(md));
        }
    }
    schema
}

fn pairs(kv: &[(String, String)]) -> Metadata {
    kv.iter()
        .map(|(k, v)| (k.as_str().into(), v.as_str().into()))
        .collect()
}

/// A list of string views declared as a list of large strings: the same
/// Parquet bytes, but pyarrow (26) cannot turn a list of string views into
/// pandas objects, and reads it as the other when the footer says so.
fn plain_strings_in_lists(dtype: &mut ArrowDataType) {
    if let ArrowDataType::LargeList(inner) | ArrowDataType::List(inner) = dtype {
        let inner = inner.as_mut();
        if inner.dtype == ArrowDataType::Utf8View {
            inner.dtype = ArrowDataType::LargeUtf8;
        }
    }
}

/// The `ARROW:schema` footer entry that Arrow readers restore the schema
/// from, with `metadata` on the schema. Encoded as Arrow does: an IPC
/// schema message behind a continuation marker and its length, in base64.
fn arrow_schema_entry(schema: &ArrowSchema, metadata: &[(String, String)]) -> (String, String) {
    use base64::Engine;
    use polars_arrow::io::ipc::write::{default_ipc_fields, schema_to_bytes};
    let mut schema = schema.clone();
    for field in schema.iter_values_mut() {
        plain_strings_in_lists(&mut field.dtype);
    }
    let ipc = default_ipc_fields(schema.iter_values());
    let bytes = schema_to_bytes(&schema, &ipc, Some(&pairs(metadata)));
    let mut framed = Vec::with_capacity(bytes.len() + 8);
    framed.extend_from_slice(&[0xFF; 4]);
    framed.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    framed.extend_from_slice(&bytes);
    (
        "ARROW:schema".into(),
        base64::engine::general_purpose::STANDARD.encode(framed),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::TableBuilder;
    use polars::prelude::{KeyValueMetadata, ParquetCompression, ParquetWriter};

    /// Three row groups of every column type tribo writes; each float
    /// value of `force_N` repeats `repeat` times (one value: `usize::MAX`).
    fn table(repeat: usize) -> Table {
        let n = 2 * ROW_GROUP_ROWS + 1234;
        let x = |i: usize| ((i / repeat) as f64 * 0.37).sin() * 1e3 + (i / repeat) as f64;
        TableBuilder::new()
            .cat_runs(
                "source",
                [(Some("a.csv"), n / 3), (Some("b.csv"), n - n / 3)],
            )
            .str_runs("section", [(Some("1"), n / 2), (None, n - n / 2)])
            .i64("stroke", (0..n).map(|i| Some((i / 1000) as i64)))
            .f64_vec("time_s", (0..n).map(|i| i as f64 * 1e-3).collect())
            .f64("force_N", (0..n).map(|i| (i % 7 != 0).then(|| x(i))))
            .build()
            .unwrap()
    }

    fn ours(t: &Table) -> Vec<u8> {
        let mut out = Vec::new();
        t.write_parquet_with(&mut out, &[("k".into(), "v".into())], &[])
            .unwrap();
        out
    }

    /// What polars' own writer gives with the same options and footer.
    fn polars_writer(t: &Table) -> Vec<u8> {
        let schema = arrow_schema(&t.df, &[]);
        let kv = vec![
            arrow_schema_entry(&schema, &[("k".into(), "v".into())]),
            ("k".into(), "v".into()),
        ];
        let mut out = Vec::new();
        ParquetWriter::new(&mut out)
            .with_compression(ParquetCompression::Snappy)
            .with_row_group_size(Some(ROW_GROUP_ROWS))
            .with_key_value_metadata(Some(KeyValueMetadata::from_static(kv)))
            .finish(&mut t.df.clone())
            .unwrap();
        out
    }

    fn read(bytes: &[u8]) -> DataFrame {
        use polars::prelude::{ParquetReader, SerReader};
        ParquetReader::new(std::io::Cursor::new(bytes))
            .finish()
            .unwrap()
    }

    /// polars' own file, byte for byte, whether the floats are distinct or
    /// few (where polars' trial finds a dictionary worthwhile, then fails
    /// to cast floats to one and writes PLAIN too); and it reads back as
    /// the table, nulls included.
    #[test]
    fn polars_own_bytes_and_values() {
        for repeat in [1, 5000, usize::MAX] {
            let t = table(repeat);
            let bytes = ours(&t);
            assert!(bytes == polars_writer(&t), "repeat {repeat}");
            assert!(read(&bytes).equals_missing(&t.df), "repeat {repeat}");
        }
    }

    /// The same bytes on one thread and on three.
    #[test]
    fn bytes_do_not_depend_on_threads() {
        let t = table(1);
        let on = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
                .install(|| ours(&t))
        };
        assert_eq!(on(1), on(3));
    }
}
