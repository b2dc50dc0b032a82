//! Wavefront MTL material libraries: the statements Tessera maps onto its materials (see
//! `mtl_material.rs`), read with their file positions so that bad values are located errors.
//!
//! Read: `newmtl`, `Kd`, `Ks`, `Ke` (three numbers, or one for grey), `Ns`, `Ni`, `d`, `Tr`,
//! `Pm` (one number), `illum` (an integer), `map_Kd`, `map_d` (a file name, relative to the MTL
//! file; texture options such as `-s` are not supported). Every other statement (`Ka`, `Tf`,
//! `map_Ks`, `bump`, ...) is ignored.
use crate::error::{InputError, Loc};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A value with the position of its statement.
#[derive(Clone, Debug, PartialEq)]
pub struct At<T> {
    /// The value.
    pub value: T,
    /// Where its statement starts.
    pub loc: Loc,
}

/// One `newmtl` block.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MtlMaterial {
    /// The material's name.
    pub name: String,
    /// Where `newmtl` is.
    pub loc: Option<Loc>,
    /// Diffuse colour `Kd`.
    pub kd: Option<At<[f32; 3]>>,
    /// Specular colour `Ks`.
    pub ks: Option<At<[f32; 3]>>,
    /// Emitted radiance `Ke`.
    pub ke: Option<At<[f32; 3]>>,
    /// Specular exponent `Ns`.
    pub ns: Option<At<f32>>,
    /// Index of refraction `Ni`.
    pub ni: Option<At<f32>>,
    /// Dissolve (opacity) `d`.
    pub d: Option<At<f32>>,
    /// Transparency `Tr` (`1 - d`).
    pub tr: Option<At<f32>>,
    /// Metalness `Pm` (the PBR extension).
    pub pm: Option<At<f32>>,
    /// Illumination model `illum`.
    pub illum: Option<At<u32>>,
    /// Diffuse texture `map_Kd`, resolved against the MTL file's folder.
    pub map_kd: Option<At<PathBuf>>,
    /// Opacity texture `map_d`, resolved against the MTL file's folder.
    pub map_d: Option<At<PathBuf>>,
}

/// `Err(what)` at `loc` unless `ok`.
fn check(ok: bool, loc: &Loc, what: String) -> Result<(), InputError> {
    if ok {
        Ok(())
    } else {
        Err(InputError::at(loc, what))
    }
}

/// Reads an MTL file.
pub(crate) fn load_mtl(path: &Path) -> Result<Vec<MtlMaterial>, InputError> {
    // Capped like scene files (64 MiB), so `/dev/zero` or a pipe named by `mtllib` cannot
    // exhaust memory.
    let text = crate::xml::source::read_text(path).map_err(|e| {
        match e.strip_prefix("cannot read file") {
            Some(rest) => InputError::file(path, format!("cannot read material library{rest}")),
            None => InputError::file(path, format!("material library: {e}")),
        }
    })?;
    parse_mtl(&text, path)
}

/// Parses MTL text read from `path`.
pub(crate) fn parse_mtl(text: &str, path: &Path) -> Result<Vec<MtlMaterial>, InputError> {
    let file = Arc::new(path.to_path_buf());
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut out: Vec<MtlMaterial> = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        let start = line.len() - line.trim_start().len();
        let mut words = line.split_whitespace();
        let Some(kw) = words.next() else { continue };
        let loc = Loc::new(file.clone(), ln as u32 + 1, start as u32 + 1);
        let rest = line[start + kw.len()..].trim();
        let err = |msg: String| InputError::at(&loc, msg);
        if kw == "newmtl" {
            if rest.is_empty() {
                return Err(err("newmtl needs a name".into()));
            }
            out.push(MtlMaterial {
                name: rest.to_string(),
                loc: Some(loc.clone()),
                ..Default::default()
            });
            continue;
        }
        let known = [
            "Kd", "Ks", "Ke", "Ns", "Ni", "d", "Tr", "Pm", "illum", "map_Kd", "map_d",
        ];
        if !known.contains(&kw) {
            continue;
        }
        let Some(m) = out.last_mut() else {
            return Err(err(format!("\"{kw}\" before the first newmtl")));
        };
        let name = m.name.clone();
        let nums = || -> Result<Vec<f32>, InputError> {
            rest.split_whitespace()
                .map(|t| match t.parse::<f32>() {
                    Ok(v) if v.is_finite() => Ok(v),
                    _ => Err(err(format!("{kw}: cannot read {t:?} as a finite number"))),
                })
                .collect()
        };
        let scalar = || -> Result<At<f32>, InputError> {
            match nums()?.as_slice() {
                [v] => Ok(At {
                    value: *v,
                    loc: loc.clone(),
                }),
                _ => Err(err(format!("{kw} needs one number"))),
            }
        };
        let color = |unit: bool| -> Result<At<[f32; 3]>, InputError> {
            let c = match nums()?.as_slice() {
                [v] => [*v; 3],
                [r, g, b] => [*r, *g, *b],
                _ => return Err(err(format!("{kw} needs three numbers (or one for grey)"))),
            };
            let range = if unit { "in [0, 1]" } else { "non-negative" };
            check(
                c.iter().all(|&v| v >= 0.0 && (!unit || v <= 1.0)),
                &loc,
                format!("{kw} of material \"{}\" must be {range}", name),
            )?;
            Ok(At {
                value: c,
                loc: loc.clone(),
            })
        };
        let unit_scalar = || -> Result<At<f32>, InputError> {
            let v = scalar()?;
            check(
                (0.0..=1.0).contains(&v.value),
                &loc,
                format!("{kw} of material \"{}\" must be in [0, 1]", name),
            )?;
            Ok(v)
        };
        let file_name = || -> Result<At<PathBuf>, InputError> {
            if rest.is_empty() {
                return Err(err(format!("{kw} needs a file name")));
            }
            if rest.starts_with('-') {
                return Err(err(format!("{kw}: texture options are not supported")));
            }
            Ok(At {
                value: dir.join(rest),
                loc: loc.clone(),
            })
        };
        match kw {
            "Kd" => m.kd = Some(color(true)?),
            "Ks" => m.ks = Some(color(true)?),
            "Ke" => m.ke = Some(color(false)?),
            "Ns" => {
                let v = scalar()?;
                check(
                    (0.0..=1e6).contains(&v.value),
                    &loc,
                    format!("Ns of material \"{}\" must be in [0, 1e6]", name),
                )?;
                m.ns = Some(v);
            }
            "Ni" => {
                let v = scalar()?;
                check(
                    v.value > 0.0,
                    &loc,
                    format!("Ni of material \"{}\" must be positive", name),
                )?;
                m.ni = Some(v);
            }
            "d" => m.d = Some(unit_scalar()?),
            "Tr" => m.tr = Some(unit_scalar()?),
            "Pm" => m.pm = Some(unit_scalar()?),
            "illum" => match rest.parse::<u32>() {
                Ok(v) if v <= 10 => {
                    m.illum = Some(At {
                        value: v,
                        loc: loc.clone(),
                    })
                }
                _ => {
                    return Err(err(format!(
                        "illum needs an integer 0 to 10, found {rest:?}"
                    )))
                }
            },
            "map_Kd" => m.map_kd = Some(file_name()?),
            "map_d" => m.map_d = Some(file_name()?),
            _ => {}
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_values_with_positions() {
        let text = "# a comment\nnewmtl red\n  Kd 0.8 0.1 0.1\nKs 0.5\nNs 40 # shiny\nKa 1 1 1\n\
                    newmtl lamp\nKe 10 8 6\nd 0.5\nmap_Kd tex/a b.png\n";
        let m = parse_mtl(text, Path::new("/x/lib.mtl")).unwrap();
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].name, "red");
        let kd = m[0].kd.as_ref().unwrap();
        assert_eq!(kd.value, [0.8, 0.1, 0.1]);
        assert_eq!((kd.loc.line, kd.loc.col), (3, 3));
        assert_eq!(m[0].ks.as_ref().unwrap().value, [0.5; 3]);
        assert_eq!(m[0].ns.as_ref().unwrap().value, 40.0);
        assert_eq!(m[1].ke.as_ref().unwrap().value, [10.0, 8.0, 6.0]);
        assert_eq!(m[1].d.as_ref().unwrap().value, 0.5);
        assert_eq!(
            m[1].map_kd.as_ref().unwrap().value,
            PathBuf::from("/x/tex/a b.png")
        );
    }

    #[test]
    fn bad_values_are_located() {
        let cases = [
            (
                "newmtl a\nKd 1.2 0 0\n",
                "lib.mtl:2:1: Kd of material \"a\" must be in [0, 1]",
            ),
            (
                "newmtl a\nKd 0.5 0.5\n",
                "lib.mtl:2:1: Kd needs three numbers",
            ),
            (
                "newmtl a\n Ns abc\n",
                "lib.mtl:2:2: Ns: cannot read \"abc\"",
            ),
            (
                "newmtl a\nNi 0\n",
                "lib.mtl:2:1: Ni of material \"a\" must be positive",
            ),
            (
                "newmtl a\nd 1.5\n",
                "lib.mtl:2:1: d of material \"a\" must be in [0, 1]",
            ),
            (
                "newmtl a\nKe -1 0 0\n",
                "lib.mtl:2:1: Ke of material \"a\" must be non-negative",
            ),
            ("Kd 1 1 1\n", "lib.mtl:1:1: \"Kd\" before the first newmtl"),
            (
                "newmtl a\nmap_Kd -s 2 2 2 t.png\n",
                "lib.mtl:2:1: map_Kd: texture options",
            ),
            ("newmtl a\nillum x\n", "lib.mtl:2:1: illum needs an integer"),
            ("newmtl\n", "lib.mtl:1:1: newmtl needs a name"),
        ];
        for (text, want) in cases {
            let e = parse_mtl(text, Path::new("lib.mtl"))
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(want), "{text:?}: {e}");
        }
    }
}
