//! 3MF: a zip package (OPC) holding `[Content_Types].xml`, `_rels/.rels` and the model
//! `3D/3dmodel.model` in the 3MF core namespace with `unit="millimeter"`, the metadata Title,
//! Designer, Application and Description, one object with the mesh, and one build item.
//! Entries are deflated with a fixed timestamp, so the same sheet gives the same bytes.

use super::error::PrintError;
use super::mesh::PrintMesh;
use crate::math::Real;
use std::fmt::Write as _;
use std::io::Write as _;

/// The model part's path in the package.
pub const MODEL_PATH: &str = "3D/3dmodel.model";

const CONTENT_TYPES: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
  <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
  <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"#;

const RELS: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
  <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"#;

/// The model's metadata (3MF core names).
#[derive(Debug, Clone, PartialEq)]
pub struct ModelMeta {
    /// `Title`.
    pub title: String,
    /// `Designer`.
    pub designer: String,
    /// `Application`.
    pub application: String,
    /// `Description`.
    pub description: String,
}

/// The 3MF package of `mesh` with `meta`.
pub fn threemf_bytes(mesh: &PrintMesh, meta: &ModelMeta) -> Result<Vec<u8>, PrintError> {
    let model = model_xml(mesh, meta);
    let encode = |e: &dyn std::fmt::Display| PrintError::Encode {
        reason: e.to_string(),
    };
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, text) in [
        ("[Content_Types].xml", CONTENT_TYPES),
        ("_rels/.rels", RELS),
        (MODEL_PATH, model.as_str()),
    ] {
        zip.start_file(name, options).map_err(|e| encode(&e))?;
        zip.write_all(text.as_bytes()).map_err(|e| encode(&e))?;
    }
    Ok(zip.finish().map_err(|e| encode(&e))?.into_inner())
}

/// The model part: XML in the 3MF core namespace.
pub fn model_xml(mesh: &PrintMesh, meta: &ModelMeta) -> String {
    let mut s = String::with_capacity(64 * (mesh.positions.len() + mesh.triangles.len()) + 1024);
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    s.push_str(
        "<model unit=\"millimeter\" xml:lang=\"en-US\" \
         xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n",
    );
    for (name, value) in [
        ("Title", &meta.title),
        ("Designer", &meta.designer),
        ("Application", &meta.application),
        ("Description", &meta.description),
    ] {
        let _ = writeln!(
            s,
            "  <metadata name=\"{name}\">{}</metadata>",
            escape(value)
        );
    }
    s.push_str("  <resources>\n");
    let _ = writeln!(
        s,
        "    <object id=\"1\" type=\"model\" name=\"{}\">\n      <mesh>\n        <vertices>",
        escape(&meta.title)
    );
    for p in &mesh.positions {
        let _ = writeln!(
            s,
            "          <vertex x=\"{}\" y=\"{}\" z=\"{}\"/>",
            num(p[0]),
            num(p[1]),
            num(p[2])
        );
    }
    s.push_str("        </vertices>\n        <triangles>\n");
    for t in &mesh.triangles {
        let _ = writeln!(
            s,
            "          <triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>",
            t[0], t[1], t[2]
        );
    }
    s.push_str("        </triangles>\n      </mesh>\n    </object>\n  </resources>\n");
    s.push_str("  <build>\n    <item objectid=\"1\"/>\n  </build>\n</model>\n");
    s
}

/// A coordinate in mm to 1e-6 mm, trailing zeros dropped.
fn num(x: Real) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" || s.is_empty() {
        "0".into()
    } else {
        s.into()
    }
}

/// Text escaped for XML content and attribute values.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\t' && c != '\n' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    fn meta() -> ModelMeta {
        ModelMeta {
            title: "isogami sheet <a&b>".into(),
            designer: "isogami 0.1.0".into(),
            application: "isogami 0.1.0".into(),
            description: "spec: IH1:0.5:1x1:a; gap_mm: 0.4".into(),
        }
    }

    fn tetra() -> PrintMesh {
        PrintMesh {
            positions: vec![
                [0.0; 3],
                [1.5, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, -0.25],
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        }
    }

    #[test]
    fn the_package_holds_the_three_parts_and_the_model_is_in_mm() {
        let bytes = threemf_bytes(&tetra(), &meta()).unwrap();
        let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes.clone())).unwrap();
        let names: Vec<String> = zip.file_names().map(String::from).collect();
        for part in ["[Content_Types].xml", "_rels/.rels", MODEL_PATH] {
            assert!(names.iter().any(|n| n == part), "{names:?}");
        }
        let mut model = String::new();
        zip.by_name(MODEL_PATH)
            .unwrap()
            .read_to_string(&mut model)
            .unwrap();
        assert!(model.contains("unit=\"millimeter\""));
        assert!(model.contains("<metadata name=\"Title\">isogami sheet &lt;a&amp;b&gt;</metadata>"));
        assert!(model.contains("<metadata name=\"Description\">spec: IH1:0.5:1x1:a; gap_mm: 0.4"));
        assert_eq!(model.matches("<vertex ").count(), 4);
        assert_eq!(model.matches("<triangle ").count(), 4);
        assert!(model.contains("<vertex x=\"1.5\" y=\"0\" z=\"0\"/>"));
        assert!(model.contains("z=\"-0.25\""));
        assert!(model.contains("<triangle v1=\"1\" v2=\"2\" v3=\"3\"/>"));
        let mut rels = String::new();
        zip.by_name("_rels/.rels")
            .unwrap()
            .read_to_string(&mut rels)
            .unwrap();
        assert!(rels.contains("Target=\"/3D/3dmodel.model\""));
        // Same input, same bytes (fixed timestamps).
        assert_eq!(threemf_bytes(&tetra(), &meta()).unwrap(), bytes);
    }

    #[test]
    fn numbers_are_short_and_never_negative_zero() {
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(-1e-9), "0");
        assert_eq!(num(12.5), "12.5");
        assert_eq!(num(3.0), "3");
    }
}
