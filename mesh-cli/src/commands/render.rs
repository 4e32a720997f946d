//! `mesh render`: a PNG picture of a mesh, optionally coloured by one of its
//! per-vertex scalars or labels (a PLY property such as `mean`, `distance`
//! or the curvature `flag`).

use mesh_kernel::MeshError;
use std::path::PathBuf;

use crate::choice::choice;
use crate::input::InputArgs;
use crate::output::{check_folder, check_output, CliResult};
use crate::render::{render_png, RenderOptions};

/// Arguments of `mesh render`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Output PNG file.
    #[arg(long)]
    out: PathBuf,
    /// Per-vertex scalar or label of the input file to colour by (e.g.
    /// `mean`, `distance`, `flag`).
    #[arg(long)]
    field: Option<String>,
    /// Picture width in pixels.
    #[arg(long, default_value_t = 800)]
    width: u32,
    /// Picture height in pixels.
    #[arg(long, default_value_t = 600)]
    height: u32,
    /// Camera azimuth in degrees.
    #[arg(long, default_value_t = -60.0, allow_negative_numbers = true)]
    azimuth: f64,
    /// Camera elevation in degrees.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true)]
    elevation: f64,
    /// The axis pointing up in the picture: x, y, z, or auto (the file
    /// format's convention: y for OBJ, PLY, OFF and glTF, z for STL and for
    /// built-in shapes).
    #[arg(long, default_value_t = Up::Auto, value_parser = choice::<Up>(Up::ALL.map(Up::name)))]
    up: Up,
}

/// The axis pointing up in a picture (`--up`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Up {
    /// The convention of the input file's format.
    Auto,
    /// +x.
    X,
    /// +y.
    Y,
    /// +z.
    Z,
}

impl Up {
    /// Every choice, in the order `--help` lists them.
    pub const ALL: [Self; 4] = [Self::Auto, Self::X, Self::Y, Self::Z];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::X => "x",
            Self::Y => "y",
            Self::Z => "z",
        }
    }

    /// The unit vector; `auto` is the convention of the input file's format
    /// ([`mesh_io::Format::conventional_up`]), z for built-in shapes.
    pub fn axis(self, input: &InputArgs) -> mesh_kernel::glam::DVec3 {
        use mesh_kernel::glam::DVec3;
        match self {
            Self::X => DVec3::X,
            Self::Y => DVec3::Y,
            Self::Z => DVec3::Z,
            Self::Auto => {
                input.path().and_then(|p| mesh_io::Format::from_path(p).ok()).map_or(DVec3::Z, |f| f.conventional_up())
            }
        }
    }
}

/// The per-vertex scalar or label `name` of `data` as numbers to colour by.
fn vertex_field<'a>(data: &'a mesh_io::MeshData, name: &str) -> CliResult<std::borrow::Cow<'a, [f64]>> {
    if let Some(values) = data.scalar(name) {
        return Ok(values.into());
    }
    if let Some(labels) = data.label(name) {
        return Ok(labels.iter().map(|&x| x as f64).collect::<Vec<f64>>().into());
    }
    let known: Vec<String> = data
        .attributes()
        .iter()
        .filter(|a| a.element == mesh_io::AttributeElement::Vertex && a.kind() != mesh_io::AttributeKind::Vector)
        .map(|a| a.name.to_owned())
        .collect();
    Err(format!("the input has no per-vertex scalar or label `{name}` (it has: {})", known.join(", ")).into())
}

mesh_kernel::named_choice!(Up, "up", MeshError);

/// Runs `mesh render`.
pub fn run(args: &Args) -> CliResult<()> {
    check_output(&args.out, args.input.path(), false)?;
    let data = args.input.load()?;
    let field = args.field.as_deref().map(|name| vertex_field(&data, name)).transpose()?;
    let scalar = field.as_deref();
    if !(args.azimuth.is_finite() && args.elevation.is_finite()) {
        return Err("camera angles must be finite".into());
    }
    let options = RenderOptions {
        width: args.width,
        height: args.height,
        azimuth: args.azimuth,
        elevation: args.elevation,
        up: args.up.axis(&args.input),
        title: args.field.clone(),
    };
    check_folder(&args.out)?;
    render_png(&data.mesh, scalar, &args.out, &options)?;
    eprintln!("wrote {}", args.out.display());
    Ok(())
}
