//! OpenPBR materials as artists exchange them: the reflection parameters of an
//! `open_pbr_surface` node in a MaterialX document (`.mtlx`).
//!
//! OpenPBR Surface is published as the MaterialX node `open_pbr_surface`
//! (OpenPBR Surface specification, "MaterialX"); a document names materials
//! (`<surfacematerial name="Brass">`) whose `surfaceshader` input points at
//! such a node:
//!
//! ```xml
//! <materialx version="1.39" colorspace="lin_rec709">
//!   <surfacematerial name="Brass" type="material">
//!     <input name="surfaceshader" type="surfaceshader" nodename="brass_shader" />
//!   </surfacematerial>
//!   <open_pbr_surface name="brass_shader" type="surfaceshader">
//!     <input name="base_color" type="color3" value="0.844, 0.782, 0.473" />
//!     <input name="base_metalness" type="float" value="1.0" />
//!   </open_pbr_surface>
//! </materialx>
//! ```
//!
//! [`read_openpbr`] reads the node's constant inputs into an [`OpenPbrSpec`]
//! (the inputs it does not set keep OpenPBR's defaults). What it does with
//! the rest:
//!
//! * an input connected to a node graph, a texture or an interface
//!   (`nodename`, `nodegraph`, `output`, `interfacename`) is an error: only
//!   constant inputs describe one BRDF;
//! * an input outside a reflection-only, isotropic BRDF (transmission,
//!   subsurface, anisotropy, thin film, emission, geometry, …) and an input
//!   this crate does not know are skipped, each named in
//!   [`MtlxMaterial::warnings`];
//! * colours are converted to linear Rec. 709 from the document's colour space
//!   (`lin_rec709`, `srgb_texture`, `acescg`; the attribute of the input or
//!   the document); a channel outside `[0, 1]` after conversion is clamped
//!   with a warning (the OpenPBR examples have `specular_color` channels up
//!   to 1.013 in ACEScg);
//! * a number outside its range (weights and roughnesses in `[0, 1]`, IORs
//!   in `[1, 1000]`) is an error.
//!
//! The spec grammar reads documents with `openpbr(file="brass.mtlx",
//! material="Brass")` (other parameters given there override the
//! document's); `radiometry preview --mtlx FILE [--material NAME]` prints the
//! warnings.

use crate::OpenPbrSpec;

/// An OpenPBR material read from a MaterialX document.
#[derive(Clone, Debug, PartialEq)]
pub struct MtlxMaterial {
    /// The material's name (the `surfacematerial`, or the shader node when
    /// the document has no material elements).
    pub name: String,
    /// Its reflection parameters (OpenPBR's defaults where the node does not
    /// set them).
    pub params: OpenPbrSpec,
    /// What was skipped or clamped, one sentence each.
    pub warnings: Vec<String>,
}

/// The OpenPBR defaults (OpenPBR Surface 1.1), energy-conserving layering.
pub fn openpbr_defaults() -> OpenPbrSpec {
    OpenPbrSpec {
        base_weight: 1.0,
        base_color: [0.8; 3],
        base_metalness: 0.0,
        base_diffuse_roughness: 0.0,
        specular_weight: 1.0,
        specular_color: [1.0; 3],
        specular_roughness: 0.3,
        specular_ior: 1.5,
        coat_weight: 0.0,
        coat_color: [1.0; 3],
        coat_roughness: 0.0,
        coat_ior: 1.6,
        fuzz_weight: 0.0,
        fuzz_color: [1.0; 3],
        fuzz_roughness: 0.5,
        coat_darkening: 1.0,
        reciprocal: false,
    }
}

/// Inputs of `open_pbr_surface` outside a reflection-only, isotropic BRDF
/// (skipped with a warning).
const OUTSIDE_PREFIXES: [&str; 6] = [
    "transmission_",
    "subsurface_",
    "thin_film_",
    "emission_",
    "geometry_",
    "base_subsurface",
];

/// Further inputs outside the BRDF this crate evaluates.
const OUTSIDE: [&str; 4] = [
    "specular_anisotropy",
    "specular_rotation",
    "coat_anisotropy",
    "coat_rotation",
];

/// Linear ACEScg (AP1, D60) to linear Rec. 709 (D65), the matrix of the
/// ACES reference rendering's output transforms (Bradford adaptation), as
/// OpenColorIO's ACES configs apply it.
const ACESCG_TO_REC709: [[f64; 3]; 3] = [
    [1.705_050_993, -0.621_792_121, -0.083_258_872],
    [-0.130_256_418, 1.140_804_737, -0.010_548_319],
    [-0.024_003_357, -0.128_968_976, 1.152_972_333],
];

/// The sRGB transfer function's inverse (IEC 61966-2-1).
fn srgb_decode(v: f64) -> f64 {
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The names of the materials of a document (its `surfacematerial`
/// elements, else its `open_pbr_surface` nodes), in document order.
pub fn material_names(xml: &str) -> Result<Vec<String>, String> {
    let doc = roxmltree::Document::parse(xml).map_err(|e| format!("not a MaterialX document: {e}"))?;
    Ok(names(&doc))
}

fn names(doc: &roxmltree::Document<'_>) -> Vec<String> {
    let mats: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("surfacematerial"))
        .filter_map(|n| n.attribute("name").map(String::from))
        .collect();
    if !mats.is_empty() {
        return mats;
    }
    doc.descendants()
        .filter(|n| n.has_tag_name("open_pbr_surface"))
        .filter_map(|n| n.attribute("name").map(String::from))
        .collect()
}

/// The `open_pbr_surface` node of material `material` (a `surfacematerial`
/// name, or the node's own name; `None`: the document's only material) in
/// the MaterialX document `xml`, read into an [`OpenPbrSpec`] (see the
/// [module docs](self)). Errors: not XML, no such material (the message
/// lists the names), several materials and none chosen, a material whose
/// shader is not an `open_pbr_surface`, a connected input, a malformed or
/// out-of-range value.
///
/// ```
/// use radiometry_spec::mtlx::read_openpbr;
/// let xml = r#"<materialx version="1.39">
///   <open_pbr_surface name="gold" type="surfaceshader">
///     <input name="base_metalness" type="float" value="1" />
///     <input name="base_color" type="color3" value="0.944, 0.776, 0.373" />
///     <input name="transmission_weight" type="float" value="0.5" />
///   </open_pbr_surface>
/// </materialx>"#;
/// let m = read_openpbr(xml, None).unwrap();
/// assert_eq!(m.name, "gold");
/// assert_eq!(m.params.base_metalness, 1.0);
/// assert_eq!(m.params.base_color, [0.944, 0.776, 0.373]);
/// assert!(m.warnings[0].contains("transmission_weight"));
/// ```
pub fn read_openpbr(xml: &str, material: Option<&str>) -> Result<MtlxMaterial, String> {
    let doc = roxmltree::Document::parse(xml).map_err(|e| format!("not a MaterialX document: {e}"))?;
    let root = doc.root_element();
    if !root.has_tag_name("materialx") {
        return Err(format!(
            "not a MaterialX document: the root element is <{}>, not <materialx>",
            root.tag_name().name()
        ));
    }
    let all = names(&doc);
    let list = || {
        if all.is_empty() {
            "the document has no surfacematerial and no open_pbr_surface".to_string()
        } else {
            format!("materials in the document: {}", all.join(", "))
        }
    };
    let shaders: Vec<roxmltree::Node<'_, '_>> = doc
        .descendants()
        .filter(|n| n.has_tag_name("open_pbr_surface"))
        .collect();
    let by_name = |name: &str| {
        shaders
            .iter()
            .copied()
            .find(|n| n.attribute("name") == Some(name))
    };
    let mats: Vec<roxmltree::Node<'_, '_>> = doc
        .descendants()
        .filter(|n| n.has_tag_name("surfacematerial"))
        .collect();
    // The shader a surfacematerial points at.
    let shader_of = |m: roxmltree::Node<'_, '_>| -> Result<roxmltree::Node<'_, '_>, String> {
        let mname = m.attribute("name").unwrap_or("?");
        let input = m
            .children()
            .find(|c| c.has_tag_name("input") && c.attribute("name") == Some("surfaceshader"))
            .ok_or_else(|| format!("material `{mname}` has no surfaceshader input"))?;
        let node = input
            .attribute("nodename")
            .ok_or_else(|| format!("material `{mname}`: its surfaceshader input names no node"))?;
        by_name(node).ok_or_else(|| {
            format!(
                "material `{mname}`: its shader `{node}` is not an open_pbr_surface node of this document"
            )
        })
    };
    let (name, shader) = match material {
        Some(want) => {
            if let Some(m) = mats.iter().find(|m| m.attribute("name") == Some(want)) {
                (want.to_string(), shader_of(*m)?)
            } else if let Some(s) = by_name(want) {
                (want.to_string(), s)
            } else {
                return Err(format!("no material `{want}` ({})", list()));
            }
        }
        None => match (mats.as_slice(), shaders.as_slice()) {
            ([m], _) => (m.attribute("name").unwrap_or("").to_string(), shader_of(*m)?),
            ([], [s]) => (s.attribute("name").unwrap_or("").to_string(), *s),
            _ => return Err(format!("choose a material ({})", list())),
        },
    };
    let doc_space = root.attribute("colorspace").unwrap_or("lin_rec709");
    let mut p = openpbr_defaults();
    let mut warnings = Vec::new();
    for input in shader.children().filter(|c| c.has_tag_name("input")) {
        let key = input.attribute("name").unwrap_or("");
        if let Some(a) = ["nodename", "nodegraph", "output", "interfacename"]
            .into_iter()
            .find(|a| input.attribute(*a).is_some())
        {
            return Err(format!(
                "input `{key}` is connected (`{a}`): textures and node graphs are not supported, only constant inputs"
            ));
        }
        if OUTSIDE_PREFIXES.iter().any(|x| key.starts_with(x)) || OUTSIDE.contains(&key) {
            warnings.push(format!(
                "`{key}` skipped: outside a reflection-only, isotropic BRDF"
            ));
            continue;
        }
        let value = input
            .attribute("value")
            .ok_or_else(|| format!("input `{key}` has no value"))?;
        let num = |lo: f64, hi: f64| -> Result<f64, String> {
            let v: f64 = value
                .trim()
                .parse()
                .map_err(|_| format!("input `{key}`: `{value}` is not a number"))?;
            if !(lo..=hi).contains(&v) {
                return Err(format!("input `{key}` = {v} is outside [{lo}, {hi}]"));
            }
            Ok(v)
        };
        let space = input.attribute("colorspace").unwrap_or(doc_space);
        let mut colour = || -> Result<[f64; 3], String> {
            let parts: Vec<f64> = value
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("input `{key}`: `{value}` is not three numbers"))?;
            let [r, g, b] = parts[..] else {
                return Err(format!("input `{key}`: `{value}` is not three numbers"));
            };
            if ![r, g, b].iter().all(|v| v.is_finite()) {
                return Err(format!("input `{key}`: `{value}` is not finite"));
            }
            let lin = match space {
                "lin_rec709" | "lin_srgb" | "linear" => [r, g, b],
                "srgb_texture" => [srgb_decode(r), srgb_decode(g), srgb_decode(b)],
                "acescg" | "lin_ap1" => {
                    let m = ACESCG_TO_REC709;
                    [0, 1, 2].map(|i| m[i][0] * r + m[i][1] * g + m[i][2] * b)
                }
                other => return Err(format!("input `{key}`: colour space `{other}` is not supported")),
            };
            let out = lin.map(|v| v.clamp(0.0, 1.0));
            if out != lin {
                warnings.push(format!(
                    "`{key}` = ({r}, {g}, {b}) in {space} is ({:.4}, {:.4}, {:.4}) in linear Rec. 709, clamped to [0, 1]",
                    lin[0], lin[1], lin[2]
                ));
            }
            Ok(out)
        };
        match key {
            "base_weight" => p.base_weight = num(0.0, 1.0)?,
            "base_color" => p.base_color = colour()?,
            "base_metalness" => p.base_metalness = num(0.0, 1.0)?,
            "base_diffuse_roughness" => p.base_diffuse_roughness = num(0.0, 1.0)?,
            "specular_weight" => p.specular_weight = num(0.0, 1.0)?,
            "specular_color" => p.specular_color = colour()?,
            "specular_roughness" => p.specular_roughness = num(0.0, 1.0)?,
            "specular_ior" => p.specular_ior = num(1.0, 1e3)?,
            "coat_weight" => p.coat_weight = num(0.0, 1.0)?,
            "coat_color" => p.coat_color = colour()?,
            "coat_roughness" => p.coat_roughness = num(0.0, 1.0)?,
            "coat_ior" => p.coat_ior = num(1.0, 1e3)?,
            "coat_darkening" => p.coat_darkening = num(0.0, 1.0)?,
            "fuzz_weight" => p.fuzz_weight = num(0.0, 1.0)?,
            "fuzz_color" => p.fuzz_color = colour()?,
            "fuzz_roughness" => p.fuzz_roughness = num(0.0, 1.0)?,
            other => warnings.push(format!(
                "`{other}` skipped: not an OpenPBR reflection parameter this crate knows"
            )),
        }
    }
    Ok(MtlxMaterial {
        name,
        params: p,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(body: &str) -> String {
        format!(r#"<?xml version="1.0"?><materialx version="1.39">{body}</materialx>"#)
    }

    const TWO: &str = r#"
      <surfacematerial name="Brass" type="material">
        <input name="surfaceshader" type="surfaceshader" nodename="brass_s" />
      </surfacematerial>
      <surfacematerial name="Paint" type="material">
        <input name="surfaceshader" type="surfaceshader" nodename="paint_s" />
      </surfacematerial>
      <open_pbr_surface name="brass_s" type="surfaceshader">
        <input name="base_color" type="color3" value="0.844, 0.782, 0.473" />
        <input name="base_metalness" type="float" value="1.0" />
        <input name="specular_roughness" type="float" value="0.02" />
      </open_pbr_surface>
      <open_pbr_surface name="paint_s" type="surfaceshader">
        <input name="coat_weight" type="float" value="1" />
        <input name="coat_ior" type="float" value="1.6" />
        <input name="specular_anisotropy" type="float" value="0.3" />
        <input name="emission_luminance" type="float" value="2" />
        <input name="sparkle" type="float" value="2" />
      </open_pbr_surface>"#;

    #[test]
    fn materials_are_chosen_by_name_and_defaults_fill_the_rest() {
        let xml = doc(TWO);
        assert_eq!(material_names(&xml).unwrap(), ["Brass", "Paint"]);
        let b = read_openpbr(&xml, Some("Brass")).unwrap();
        assert_eq!(b.params.base_color, [0.844, 0.782, 0.473]);
        assert_eq!(b.params.base_metalness, 1.0);
        assert_eq!(b.params.specular_roughness, 0.02);
        assert_eq!(b.params.specular_ior, 1.5, "default");
        assert!(b.warnings.is_empty());
        // By shader name too.
        assert_eq!(read_openpbr(&xml, Some("brass_s")).unwrap().params, b.params);
        let p = read_openpbr(&xml, Some("Paint")).unwrap();
        assert_eq!((p.params.coat_weight, p.params.coat_ior), (1.0, 1.6));
        assert_eq!(p.warnings.len(), 3, "{:?}", p.warnings);
        assert!(p.warnings.iter().any(|w| w.contains("specular_anisotropy")));
        assert!(p.warnings.iter().any(|w| w.contains("emission_luminance")));
        assert!(p.warnings.iter().any(|w| w.contains("sparkle")));
    }

    #[test]
    fn ambiguity_missing_names_and_connections_are_errors() {
        let xml = doc(TWO);
        let e = read_openpbr(&xml, None).unwrap_err();
        assert!(
            e.contains("choose a material") && e.contains("Brass, Paint"),
            "{e}"
        );
        let e = read_openpbr(&xml, Some("Gold")).unwrap_err();
        assert!(
            e.contains("no material `Gold`") && e.contains("Brass, Paint"),
            "{e}"
        );
        let tex = doc(r#"<open_pbr_surface name="s" type="surfaceshader">
              <input name="base_color" type="color3" nodename="image1" /></open_pbr_surface>"#);
        let e = read_openpbr(&tex, None).unwrap_err();
        assert!(e.contains("connected") && e.contains("base_color"), "{e}");
        assert!(
            read_openpbr("<notxml", None)
                .unwrap_err()
                .contains("not a MaterialX document")
        );
        assert!(read_openpbr("<foo/>", None).unwrap_err().contains("<foo>"));
        let bad = doc(r#"<open_pbr_surface name="s" type="surfaceshader">
              <input name="specular_ior" type="float" value="0.5" /></open_pbr_surface>"#);
        assert!(
            read_openpbr(&bad, None)
                .unwrap_err()
                .contains("outside [1, 1000]")
        );
        let bad = doc(r#"<open_pbr_surface name="s" type="surfaceshader">
              <input name="base_color" type="color3" value="0.5, 0.5" /></open_pbr_surface>"#);
        assert!(read_openpbr(&bad, None).unwrap_err().contains("three numbers"));
    }

    /// ACEScg → linear Rec. 709: white stays white (both D60/D65 whites map
    /// to equal channels within the matrix's rounding), a channel pushed
    /// out of gamut is clamped with a warning; sRGB-encoded colours are
    /// decoded (0.5 → 0.2140).
    #[test]
    fn colour_spaces_convert_to_linear_rec709() {
        let aces = r#"<?xml version="1.0"?><materialx version="1.39" colorspace="acescg">
          <open_pbr_surface name="s" type="surfaceshader">
            <input name="base_color" type="color3" value="1, 1, 1" />
            <input name="specular_color" type="color3" value="0.963, 0.977, 1.013" />
            <input name="coat_color" type="color3" value="0.5, 0.5, 0.5" colorspace="srgb_texture" />
          </open_pbr_surface></materialx>"#;
        let m = read_openpbr(aces, None).unwrap();
        for c in m.params.base_color {
            assert!((c - 1.0).abs() < 1e-6 || c == 1.0, "{:?}", m.params.base_color);
        }
        for c in m.params.coat_color {
            assert!((c - 0.214_041).abs() < 1e-5, "{c}");
        }
        assert!(m.params.specular_color.iter().all(|c| (0.0..=1.0).contains(c)));
        // 0.963, 0.977, 1.013 in AP1: blue above 1 in Rec. 709 → clamped.
        assert!(
            m.warnings
                .iter()
                .any(|w| w.contains("specular_color") && w.contains("clamped")),
            "{:?}",
            m.warnings
        );
    }

    /// The grammar: `openpbr(file="…", material="…")` reads the document;
    /// explicit parameters override it; errors point at the file name.
    #[test]
    fn the_grammar_reads_documents() {
        let dir = std::env::temp_dir().join(format!("radiometry-mtlx-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("two.mtlx");
        std::fs::write(&path, doc(TWO)).unwrap();
        let p = path.display();
        let crate::BrdfSpec::OpenPbr(b) = crate::parse_brdf(&format!(
            r#"openpbr(file="{p}", material="Brass", specular_roughness=0.4)"#
        ))
        .unwrap() else {
            panic!("not openpbr")
        };
        assert_eq!(b.base_color, [0.844, 0.782, 0.473]);
        assert_eq!((b.base_metalness, b.specular_roughness), (1.0, 0.4));
        let e = crate::parse_brdf(&format!(r#"openpbr(file="{p}")"#)).unwrap_err();
        assert!(e.message.contains("choose a material"), "{e}");
        let e = crate::parse_brdf(r#"openpbr(file="/nonexistent/x.mtlx")"#).unwrap_err();
        assert!(e.message.contains("cannot read"), "{e}");
        let e = crate::parse_brdf(r#"openpbr(material="Brass")"#).unwrap_err();
        assert!(e.message.contains("needs `file`"), "{e}");
        let e = crate::parse_brdf(r#"openpbr(file=3)"#).unwrap_err();
        assert!(e.message.contains("string"), "{e}");
        let e = crate::parse_brdf(r#"openpbr(file="unterminated)"#).unwrap_err();
        assert!(e.message.contains("unterminated"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
