//! Instron Bluehill raw-data CSV export.
//!
//! Layout: a results block of `Name,"value",unit` lines (Modulus (Automatic
//! Young's), Length, Thickness, Width, Tensile stress at Tensile strength,
//! Tensile strain at Tensile strength, …), a blank line, the channel names
//! (Time, Extension, Load, Tensile strain (Strain 1), Tensile stress), a
//! unit row in parentheses (`(s),(mm),(N),(%),(MPa)`), then quoted numbers
//! with thousands separators (`"10,166.89062"`); CRLF line endings.
//!
//! Each results line is kept with its name as the key and `value unit` as
//! the value (the generic metadata parser would split at the first comma
//! inside the quotes).

use crate::error::Result;
use crate::ingest::dialect::split_fields;
use crate::ingest::formats::delimited::read_delimited_rekeyed;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The Bluehill raw-data reader.
pub struct Bluehill;

impl Reader for Bluehill {
    fn name(&self) -> &'static str {
        "instron-bluehill"
    }
    fn description(&self) -> &'static str {
        "Instron Bluehill raw-data CSV (results block, unit row in parentheses, thousands separators)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        let head = text.head(30);
        head.iter().any(|l| l.contains("at Tensile strength"))
            || head.iter().any(|l| l.starts_with("Modulus (Automatic"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        read_delimited_rekeyed(text, options, |line, m| {
            let fields = split_fields(line, ',');
            let fields: Vec<&str> = fields.iter().map(|f| f.trim()).collect();
            if let Some((k, rest)) = fields.split_first() {
                m.key = k.to_string();
                m.value = rest
                    .iter()
                    .filter(|f| !f.is_empty())
                    .copied()
                    .collect::<Vec<_>>()
                    .join(" ");
            }
            Ok(())
        })
    }
}
