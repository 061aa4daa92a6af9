//! The Cattaneo–Mindlin benchmark, plane strain (`scenes/mindlin.toml`):
//! the lower half of a cylinder pressed onto a block of the same material
//! and then shifted tangentially with the press held, Coulomb friction,
//! against Mindlin's partial-slip solution.
//!
//! With `P` the press and `Q < mu P` the tangential load (per unit
//! thickness; the reactions of the supports `press` and `shift`), Hertz's
//! half-width `a = sqrt(4 P R / (pi E*))` and peak `p0 = 2 P / (pi a)`,
//! two identical elastic bodies stick on `|x| < c = a sqrt(1 - Q / (mu
//! P))` and slip outside it, with the shear
//!
//! ```text
//! q(x) = mu p0 sqrt(1 - x^2/a^2) - mu p0 (c/a) sqrt(1 - x^2/c^2)   |x| < c
//! q(x) = mu p0 sqrt(1 - x^2/a^2)                                   c <= |x| <= a
//! ```
//!
//! (Johnson, *Contact Mechanics*, 7.2). The solve's nodal table
//! (`contact.csv`) gives every slave node's position, pressure, shear and
//! state; `x` is measured from the pressure's centroid. What is compared:
//! the stick zone's half-width (half the distance between its outermost
//! sticking nodes) against `c`; the nodal shear against `q` (its RMS error
//! over the nodes in contact, relative to `mu p0`); and that every sliding
//! node carries exactly `mu p`. `cargo run --release --example mindlin`
//! prints the refinement table of docs/benchmarks.md.

use std::path::Path;
use std::time::Instant;

use solver::contact::NodalContactRow;
use solver::report::{ContactTable, FrictionTable, RowFriction};
use solver::scene::MeshSpec;
use solver::{Dim, Scene, Solution, SolveOptions, State, solve};

use super::contact_modulus;

/// The meshes of the refinement table: `(h, file)` in `scenes/`
/// (`scripts/make-mindlin-mesh.py h`).
pub const MESHES: [(f64, &str); 3] = [
    (0.4, "mindlin-coarse.msh"),
    (0.2, "mindlin-medium.msh"),
    (0.1, "mindlin.msh"),
];

/// The cylinder's radius in `scenes/mindlin.toml`.
pub const RADIUS: f64 = 10.0;

/// Mindlin's shear magnitude at `x` (module docs) for a contact of
/// half-width `a`, stick half-width `c`, peak `p0` and coefficient `mu`.
pub fn mindlin_shear(x: f64, a: f64, c: f64, mu: f64, p0: f64) -> f64 {
    let ellipse = |w: f64| (1.0 - (x / w).powi(2)).max(0.0).sqrt();
    if x.abs() < c {
        mu * p0 * (ellipse(a) - c / a * ellipse(c))
    } else {
        mu * p0 * ellipse(a)
    }
}

/// One slave node of the nodal table.
#[derive(Debug, Clone, PartialEq)]
pub struct MindlinNode {
    /// Current x.
    pub x: f64,
    /// The pressure `p`.
    pub pressure: f64,
    /// The shear's magnitude, `|(shear_x, shear_y)|`.
    pub shear: f64,
    /// The tributary length.
    pub tributary: f64,
    /// `open`, `stick` or `slip`.
    pub state: String,
}

/// What one solve of the benchmark gives (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct MindlinMeasured {
    /// Coulomb's coefficient.
    pub mu: f64,
    /// The press `P` (per unit thickness).
    pub press: f64,
    /// The tangential load `Q`.
    pub shift: f64,
    /// Hertz's half-width `a`.
    pub a: f64,
    /// Hertz's peak `p0`.
    pub p0: f64,
    /// Mindlin's stick half-width `c`.
    pub c: f64,
    /// The pressure's centroid (x is measured from it).
    pub centre: f64,
    /// The outermost sticking nodes, from the centre (`None`: none sticks).
    pub stick: Option<(f64, f64)>,
    /// The nodes in contact (`p > 0`).
    pub in_contact: usize,
    /// The RMS of `(|q_node| - q(x)) / (mu p0)` over the nodes in contact
    /// (`|q_node|` the magnitude of the nodal shear).
    pub shear_rms: f64,
    /// The largest `||q| - mu p| / (mu p)` over the sliding nodes.
    pub slip_bound: f64,
    /// The nodes, sorted by x.
    pub nodes: Vec<MindlinNode>,
}

impl MindlinMeasured {
    /// Half the width of the stick zone.
    pub fn stick_half_width(&self) -> Option<f64> {
        self.stick.map(|(l, r)| 0.5 * (r - l))
    }
}

/// Why the benchmark could not be measured.
#[derive(Debug, thiserror::Error)]
pub enum MindlinError {
    /// The scene.
    #[error(transparent)]
    Scene(#[from] solver::SceneError),
    /// The solve.
    #[error("{mesh}: {source}")]
    Solve {
        /// The mesh file.
        mesh: String,
        /// What the solver said.
        source: Box<solver::SolverError>,
    },
    /// The nodal table or the reactions.
    #[error("{0}")]
    Table(String),
}

/// The nodal contact table of `state` with each row's friction columns
/// (what `contact.csv` writes).
fn table(
    sol: &Solution,
    state: &State,
) -> Result<Vec<(NodalContactRow, RowFriction<2>)>, MindlinError> {
    let rows = <Dim<2> as ContactTable<2>>::rows(sol, state)
        .map_err(|e| MindlinError::Table(e.to_string()))?;
    let friction = FrictionTable::new(sol, state);
    Ok(rows
        .into_iter()
        .map(|r| {
            let f = friction.columns(sol, state, &r);
            (r, f)
        })
        .collect())
}

/// Measures a solve of `scenes/mindlin.toml` (or a scene of its groups)
/// with coefficient `mu`, material `young`, `poisson` (module docs).
pub fn measure(
    sol: &Solution,
    mu: f64,
    young: f64,
    poisson: f64,
) -> Result<MindlinMeasured, MindlinError> {
    let mut nodes: Vec<MindlinNode> = table(sol, &sol.final_state)?
        .into_iter()
        .map(|(row, friction)| MindlinNode {
            x: row.position[0],
            pressure: row.pressure,
            shear: friction.shear[0].hypot(friction.shear[1]),
            tributary: row.tributary_length,
            state: friction.state.name().to_owned(),
        })
        .collect();
    nodes.sort_by(|a, b| a.x.total_cmp(&b.x));
    let reaction = |name: &str| {
        let k = sol
            .support_groups
            .iter()
            .position(|g| g == name)
            .ok_or_else(|| MindlinError::Table(format!("no support group {name}")))?;
        sol.step_records
            .last()
            .map(|r| r.reactions[k])
            .ok_or_else(|| MindlinError::Table("no converged step".to_owned()))
    };
    let press = -reaction("press")?[1];
    let shift = reaction("shift")?[0].abs();
    let e_star = contact_modulus(young, poisson);
    let a = (4.0 * press * RADIUS / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * press / (std::f64::consts::PI * a);
    let c = a * (1.0 - shift / (mu * press)).max(0.0).sqrt();
    let contact: Vec<&MindlinNode> = nodes.iter().filter(|n| n.pressure > 0.0).collect();
    let load: f64 = contact.iter().map(|n| n.pressure * n.tributary).sum();
    let centre = contact
        .iter()
        .map(|n| n.x * n.pressure * n.tributary)
        .sum::<f64>()
        / load;
    let sticking: Vec<f64> = contact
        .iter()
        .filter(|n| n.state == "stick")
        .map(|n| n.x - centre)
        .collect();
    let stick = sticking.first().zip(sticking.last()).map(|(&l, &r)| (l, r));
    let squares: f64 = contact
        .iter()
        .map(|n| ((n.shear - mindlin_shear(n.x - centre, a, c, mu, p0)) / (mu * p0)).powi(2))
        .sum();
    let slip_bound = contact
        .iter()
        .filter(|n| n.state == "slip")
        .map(|n| (n.shear - mu * n.pressure).abs() / (mu * n.pressure))
        .fold(0.0, f64::max);
    Ok(MindlinMeasured {
        mu,
        press,
        shift,
        a,
        p0,
        c,
        centre,
        stick,
        in_contact: contact.len(),
        shear_rms: (squares / contact.len().max(1) as f64).sqrt(),
        slip_bound,
        nodes,
    })
}

/// One row of the refinement table.
#[derive(Debug, Clone)]
pub struct MindlinRow {
    /// The mesh script's `h`.
    pub h: f64,
    /// The mesh file.
    pub mesh: &'static str,
    /// What was measured.
    pub measured: MindlinMeasured,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Wall time of the solve.
    pub seconds: f64,
}

/// The scene `scenes_dir/mindlin.toml` on the mesh `file`.
pub fn scene_on(scenes_dir: &Path, file: &str) -> Result<Scene, MindlinError> {
    let mut scene = Scene::from_file(scenes_dir.join("mindlin.toml"))?;
    scene.mesh = Some(MeshSpec {
        file: file.to_string(),
    });
    Ok(scene)
}

/// Solves and measures `scenes_dir/mindlin.toml` on `file`.
pub fn solve_on(scenes_dir: &Path, h: f64, file: &'static str) -> Result<MindlinRow, MindlinError> {
    let scene = scene_on(scenes_dir, file)?;
    let (young, poisson) = scene
        .material
        .as_ref()
        .map(|m| (m.young, m.poisson))
        .ok_or_else(|| MindlinError::Table("the scene has no [material]".to_owned()))?;
    let mu = scene.contacts.first().map_or(0.0, |c| c.friction);
    let start = Instant::now();
    let sol =
        solve(&scene, &SolveOptions::from_scene(&scene)).map_err(|source| MindlinError::Solve {
            mesh: file.to_string(),
            source: Box::new(source),
        })?;
    Ok(MindlinRow {
        h,
        mesh: file,
        measured: measure(&sol, mu, young, poisson)?,
        newton_iterations: sol.newton_iterations,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// A cyclic tangential load on the Mindlin scene: the shift goes to `+d`,
/// back to `-d` and again to `+d` with the press held (module docs of
/// [`hysteresis`]).
#[derive(Debug, Clone)]
pub struct Hysteresis {
    /// `(delta, Q)` at every converged step of the shift: the top edge's
    /// tangential displacement and the reaction of `shift`.
    pub points: Vec<(f64, f64)>,
    /// The work of `Q` over the closed cycle (from the first `+d` back to
    /// it, trapezoidal in the steps): the energy dissipated.
    pub external_work: f64,
    /// The friction's dissipation over the same cycle: per step and
    /// sliding node `W_a |q_a| |slip increment|` (the tributary length,
    /// the shear at the step's end, the growth of the accumulated slip).
    pub friction_work: f64,
    /// `|Q(end) - Q(first +d)| / Q(first +d)`: how far from closed the
    /// loop is.
    pub closure: f64,
}

/// The Mindlin scene on `file` with the shift cycled `+d, -d, +d` over
/// load factors 0.5..1 (`d` the scene's shift, in `steps` equal steps):
/// the loop, the work of `Q` over the closed cycle and the friction's
/// dissipation, which an energy balance equates (the elastic energy
/// returns to its value at the first `+d`).
pub fn hysteresis(scenes_dir: &Path, file: &str, steps: usize) -> Result<Hysteresis, MindlinError> {
    let mut scene = scene_on(scenes_dir, file)?;
    let shift = scene
        .prescribes
        .iter_mut()
        .find(|p| p.name.as_deref() == Some("shift"))
        .ok_or_else(|| MindlinError::Table("no prescribe `shift`".to_owned()))?;
    shift.amplitude = Some(vec![
        [0.0, 0.0],
        [0.5, 0.0],
        [0.625, 1.0],
        [0.875, -1.0],
        [1.0, 1.0],
    ]);
    scene.loading.steps = vec![steps];
    let opts = SolveOptions {
        record_steps: true,
        steps,
        ..SolveOptions::from_scene(&scene)
    };
    let sol = solve::<2>(&scene, &opts).map_err(|source| MindlinError::Solve {
        mesh: file.to_string(),
        source: Box::new(source),
    })?;
    let k = sol
        .support_groups
        .iter()
        .position(|g| g == "shift")
        .ok_or_else(|| MindlinError::Table("no support group shift".to_owned()))?;
    // a node of the top edge (y = R): its x displacement is the shift
    let top = sol
        .mesh
        .nodes_ref
        .iter()
        .position(|x| (x[1] - RADIUS).abs() < 1e-9)
        .ok_or_else(|| MindlinError::Table("no node at y = R".to_owned()))?;
    let mut points = Vec::new();
    let mut slips: Vec<Vec<(f64, f64, f64)>> = Vec::new();
    for (record, state) in sol.step_records.iter().zip(&sol.snapshots[1..]) {
        if record.load_factor <= 0.5 + 1e-12 {
            continue;
        }
        points.push((state.displacements[top][0], record.reactions[k][0]));
        // (tributary, |shear|, accumulated slip) per row
        let rows = table(&sol, state)?
            .into_iter()
            .map(|(r, f)| {
                (
                    r.tributary_length,
                    f.shear[0].hypot(f.shear[1]),
                    f.slip.unwrap_or(0.0),
                )
            })
            .collect();
        slips.push(rows);
    }
    // the closed cycle: from the first return to +d (a quarter of the
    // shift's steps in) to the end
    let first_peak = points.len() / 4 - 1;
    let mut external = 0.0;
    let mut friction = 0.0;
    for s in first_peak + 1..points.len() {
        let ((d0, q0), (d1, q1)) = (points[s - 1], points[s]);
        external += 0.5 * (q0 + q1) * (d1 - d0);
        friction += slips[s]
            .iter()
            .zip(&slips[s - 1])
            .map(|(now, before)| now.0 * now.1 * (now.2 - before.2))
            .sum::<f64>();
    }
    let (q_peak, q_end) = (points[first_peak].1, points[points.len() - 1].1);
    Ok(Hysteresis {
        closure: (q_end - q_peak).abs() / q_peak.abs(),
        points,
        external_work: external,
        friction_work: friction,
    })
}

/// The refinement table (Markdown).
pub fn markdown(rows: &[MindlinRow]) -> String {
    let mut out = String::from(
        "| h | nodes in contact | P | Q / (mu P) | a | c | stick half-width | (w - c) / a | centre | shear RMS / (mu p0) | sliding: max \\|\\|q\\| - mu p\\| / (mu p) | Newton | s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let m = &r.measured;
        let w = m.stick_half_width();
        out.push_str(&format!(
            "| {} | {} | {:.4} | {:.4} | {:.4} | {:.4} | {} | {} | {:+.4} | {:.3} | {:.1e} | {} | {:.2} |\n",
            r.h,
            m.in_contact,
            m.press,
            m.shift / (m.mu * m.press),
            m.a,
            m.c,
            w.map_or("-".to_owned(), |w| format!("{w:.4}")),
            w.map_or("-".to_owned(), |w| format!("{:+.3}", (w - m.c) / m.a)),
            m.centre,
            m.shear_rms,
            m.slip_bound,
            r.newton_iterations,
            r.seconds
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The coarse mesh (h = 0.4, about 13 nodes in contact): partial slip
    /// with the stick zone where Mindlin puts it to within one node
    /// spacing (about 0.17), every sliding node at `mu p` to round-off,
    /// and more slip with a larger shift.
    #[test]
    fn the_stick_zone_is_mindlins_on_the_coarse_mesh() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let row = solve_on(&dir, 0.4, "mindlin-coarse.msh").unwrap();
        let m = &row.measured;
        let ratio = m.shift / (m.mu * m.press);
        assert!((0.4..0.6).contains(&ratio), "Q / (mu P) = {ratio}");
        assert!((m.a - 1.1).abs() < 0.05, "a = {}", m.a);
        let w = m.stick_half_width().unwrap();
        assert!(
            (w - m.c).abs() < 0.2,
            "stick half-width {w} against c = {}",
            m.c
        );
        assert!(m.slip_bound < 1e-9, "{}", m.slip_bound);
        // every node well inside c sticks, every node in contact well
        // outside it slips
        for n in m.nodes.iter().filter(|n| n.pressure > 0.0) {
            let x = (n.x - m.centre).abs();
            if x < m.c - 0.35 {
                assert_eq!(n.state, "stick", "{n:?}");
            }
            if x > m.c + 0.2 {
                assert_eq!(n.state, "slip", "{n:?}");
            }
        }
        assert!(m.shear_rms < 0.5, "{}", m.shear_rms);
    }

    /// Shift +d, -d, +d on the coarse mesh: the loop closes and the work
    /// of the tangential load over the cycle is the friction's
    /// dissipation.
    #[test]
    fn the_hysteresis_loop_closes_and_its_area_is_the_frictions_work() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let h = hysteresis(&dir, "mindlin-coarse.msh", 80).unwrap();
        assert_eq!(h.points.len(), 40);
        assert!(h.closure < 1e-2, "closure {}", h.closure);
        assert!(h.external_work > 0.0);
        let balance = (h.external_work - h.friction_work).abs() / h.external_work;
        assert!(
            balance < 0.1,
            "work of Q {} against friction's {}",
            h.external_work,
            h.friction_work
        );
    }

    #[test]
    fn mindlins_shear_is_continuous_at_the_stick_edge_and_zero_at_the_contact_edge() {
        let (a, c, mu, p0) = (1.0, 0.6, 0.3, 2.0);
        let inside = mindlin_shear(c - 1e-12, a, c, mu, p0);
        let outside = mindlin_shear(c + 1e-12, a, c, mu, p0);
        assert!((inside - outside).abs() < 1e-5);
        assert_eq!(mindlin_shear(a, a, c, mu, p0), 0.0);
        // no tangential load (c = a): no shear anywhere
        assert_eq!(mindlin_shear(0.3, a, a, mu, p0), 0.0);
    }
}
