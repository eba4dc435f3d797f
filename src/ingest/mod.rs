//! Ingestion of instrument exports into SI channels.
