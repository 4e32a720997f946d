//! What each format can store of a [`MeshView`], so that a writer never
//! leaves an attribute out without saying so ([`crate::WriteReport::dropped`]).

use crate::attribute::AttributeElement;
use crate::data::MeshView;
use crate::format::Format;

/// The attributes a format stores.
#[derive(Debug, Clone, Copy)]
struct Holds {
    normals: bool,
    uvs: bool,
    corner_uvs: bool,
    colors: bool,
    /// Colour alpha as well as red, green and blue.
    alpha: bool,
    /// Named per-vertex attributes.
    vertex_attributes: bool,
    /// Named per-face attributes.
    face_attributes: bool,
}

impl Holds {
    fn of(format: Format) -> Self {
        let all = Self {
            normals: true,
            uvs: true,
            corner_uvs: true,
            colors: true,
            alpha: true,
            vertex_attributes: true,
            face_attributes: true,
        };
        match format {
            Format::Ply => all,
            Format::Gltf | Format::Glb => Self { face_attributes: false, ..all },
            Format::Obj => Self { alpha: false, vertex_attributes: false, face_attributes: false, ..all },
            Format::Off => Self { corner_uvs: false, vertex_attributes: false, face_attributes: false, ..all },
            Format::Stl => Self {
                normals: false,
                uvs: false,
                corner_uvs: false,
                colors: false,
                alpha: false,
                vertex_attributes: false,
                face_attributes: false,
            },
        }
    }
}

/// What of `view` `format` cannot store, one phrase each (`normals`,
/// `face scalar `distortion``, `colour alpha`), in the view's order. Per-vertex
/// texture coordinates next to corner ones are not listed: every format
/// writes the corner ones instead, as documented. O(V) for the alpha check,
/// else O(number of attributes).
pub(crate) fn dropped(format: Format, view: &MeshView<'_>) -> Vec<String> {
    let holds = Holds::of(format);
    let standard = [
        (view.normals.is_some(), holds.normals, "normals"),
        (view.uvs.is_some() && view.corner_uvs.is_none(), holds.uvs, "texture coordinates"),
        (view.corner_uvs.is_some(), holds.corner_uvs, "corner texture coordinates"),
        (view.colors.is_some(), holds.colors, "colours"),
    ];
    let mut out: Vec<String> =
        standard.iter().filter(|(present, held, _)| *present && !held).map(|(_, _, what)| (*what).to_owned()).collect();
    let translucent = view.colors.is_some_and(|c| c.iter().any(|rgba| rgba[3] != 1.0));
    if holds.colors && !holds.alpha && translucent {
        out.push("colour alpha".to_owned());
    }
    let held = |element| match element {
        AttributeElement::Vertex => holds.vertex_attributes,
        AttributeElement::Face => holds.face_attributes,
    };
    out.extend(view.attributes.iter().filter(|a| !held(a.element)).map(ToString::to_string));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use mesh_kernel::TriMesh;

    #[test]
    fn each_format_names_what_it_leaves_out() {
        let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let (normals, k, chart) = ([DVec3::Z; 3], [1.0; 3], [4i64]);
        let colors = [[1.0, 0.0, 0.0, 0.5]; 3];
        let view = MeshView::new(&mesh)
            .with_normals(&normals)
            .with_colors(&colors)
            .with_scalar("k", &k)
            .with_face_label("chart", &chart);
        assert!(dropped(Format::Ply, &view).is_empty());
        assert_eq!(dropped(Format::Glb, &view), ["face label `chart`"]);
        assert_eq!(dropped(Format::Obj, &view), ["colour alpha", "vertex scalar `k`", "face label `chart`"]);
        assert_eq!(dropped(Format::Off, &view), ["vertex scalar `k`", "face label `chart`"]);
        assert_eq!(dropped(Format::Stl, &view), ["normals", "colours", "vertex scalar `k`", "face label `chart`"]);
    }
}
