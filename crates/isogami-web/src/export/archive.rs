//! A folder export (named files, e.g. kirigami_sim's four text files) as one zip archive for
//! download. Entries are stored uncompressed (the zip crate is built without compression:
//! the files are small text) under their plain names, so unzipping gives the folder
//! `isogami export --out DIR` writes.

use crate::error::{ApiError, ApiResult};
use std::io::{Cursor, Write};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

/// The zip archive of `files` (name, contents), in their order.
pub fn zip_files(files: &[(&str, Vec<u8>)]) -> ApiResult<Vec<u8>> {
    let fail = |e: &dyn std::fmt::Display| ApiError::internal(format!("zip: {e}"));
    let mut zip = ZipWriter::new(Cursor::new(Vec::new()));
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .unix_permissions(0o644);
    for (name, bytes) in files {
        zip.start_file(*name, options).map_err(|e| fail(&e))?;
        zip.write_all(bytes).map_err(|e| fail(&e))?;
    }
    Ok(zip.finish().map_err(|e| fail(&e))?.into_inner())
}
