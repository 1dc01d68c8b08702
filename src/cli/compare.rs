//! `slice2solid compare MESH REFERENCE [--json] [--samples N] [--seed S]`.
use crate::CompareArgs;
use slice2solid::eval::compare::compare_meshes;
use slice2solid::io::mesh::read_trimesh;
use slice2solid::Result;
use std::process::ExitCode;

pub fn run(args: CompareArgs) -> Result<ExitCode> {
    let mesh = read_trimesh(&args.mesh)?;
    let reference = read_trimesh(&args.reference)?;
    let r = compare_meshes(&mesh, &reference, args.samples, args.seed);
    if args.json {
        super::print_json(&r)?;
    } else {
        println!(
            "{} vs {} (distances / reference diagonal {:.6e})",
            args.mesh.display(),
            args.reference.display(),
            r.reference_diagonal
        );
        println!(
            "  iou                 {:.6}  ({} lines; volumes {:.6e} / {:.6e})",
            r.iou, r.iou_lines, r.volume_mesh, r.volume_reference
        );
        println!(
            "  chamfer_l1          {:.6e}  (sample to sample, {} each way)",
            r.chamfer_l1, r.samples
        );
        println!("  chamfer_l2          {:.6e}", r.chamfer_l2);
        println!("  hausdorff           {:.6e}", r.hausdorff);
        println!(
            "  chamfer_l1_surface  {:.6e}  (sample to surface)",
            r.chamfer_l1_surface
        );
        println!("  chamfer_l2_surface  {:.6e}", r.chamfer_l2_surface);
        println!("  hausdorff_surface   {:.6e}", r.hausdorff_surface);
        if !(r.mesh_closed && r.reference_closed) {
            println!("  note: a mesh is not closed; the IoU uses nonzero winding along lines (best effort)");
        }
    }
    Ok(ExitCode::SUCCESS)
}
