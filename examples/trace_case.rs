//! Prints per-frame statistics of an evolution on a case folder: `trace_case DIR [EVERY]`.
use topocontour::cli::{init_shapes, params_for, SegmentArgs};
use topocontour::evolution::Evolver;
use topocontour::io::load_image;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let dir = std::path::PathBuf::from(&a[1]);
    let every: usize = a.get(2).map_or(50, |s| s.parse().unwrap());
    let args = SegmentArgs::from_case(&dir).unwrap_or_else(|f| panic!("{}", f.message));
    let image = load_image(&args.image).unwrap();
    let mut params = params_for(&args.run).unwrap();
    if let Ok(w) = std::env::var("W") {
        let v: Vec<f64> = w.split(',').map(|x| x.parse().unwrap()).collect();
        params.weights = topocontour::evolution::ForceWeights {
            region: v[0],
            balloon: v[1],
            edge: v[2],
            stretch: v[3],
            bend: v[4],
        };
    }
    let mut ev = Evolver::new(
        &image,
        &init_shapes(&args.run, image.width, image.height).unwrap(),
        params,
    )
    .unwrap();
    println!("model {:?}", ev.model());
    while !ev.is_converged() && ev.frames() < 3000 {
        let f = ev.step();
        if f.index.is_multiple_of(every) || !f.events.is_empty() || f.converged {
            println!("frame {} level {} verts {} contours {} area {:.1} speed {:.3} active {:.3} energy {:.1} events {:?}", f.index, f.level, f.vertices, f.contours, f.area, f.mean_speed, f.active_share, f.energy, f.events);
        }
    }
}
