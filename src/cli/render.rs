//! `slice2solid render MESH [--sections IN] -o OUT.png [--size WxH] [--view AZ,EL]`.
use crate::RenderArgs;
use slice2solid::io::{mesh::read_trimesh, read_sections};
use slice2solid::render::render;
use slice2solid::Result;
use std::process::ExitCode;

pub fn run(args: RenderArgs) -> Result<ExitCode> {
    let mesh = read_trimesh(&args.mesh)?;
    let sections = args.sections.as_deref().map(read_sections).transpose()?;
    let image = render(&mesh, sections.as_ref(), args.size, args.view)?;
    image.write_png(&args.output)?;
    eprintln!(
        "{}: {}x{} picture of {} triangles",
        args.output.display(),
        image.width,
        image.height,
        mesh.triangles.len()
    );
    Ok(ExitCode::SUCCESS)
}
