//! `gapsim run --out DIR` writes `DIR/reactions.csv`: one row per converged
//! step, `step,load_factor`, then `<group>_x,<group>_y` per support group
//! (issue #7), on the large-sliding benchmark.

use std::process::Command;

#[test]
fn run_writes_the_reactions_of_every_group_and_step() {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-reactions-{}", std::process::id()));
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/sliding.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(["run", scene, "--steps", "20", "--out"])
        .arg(&dir)
        .output()
        .expect("run gapsim");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("reactions.csv")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0],
        [
            "step",
            "load_factor",
            "base_x",
            "base_y",
            "press_x",
            "press_y",
            "slide_x",
            "slide_y"
        ]
    );
    assert_eq!(rows.len(), 21, "{csv}");
    for (k, row) in rows[1..].iter().enumerate() {
        let v: Vec<f64> = row.iter().map(|s| s.parse().unwrap()).collect();
        assert_eq!(v[0], (k + 1) as f64);
        assert_eq!(v[1], (k + 1) as f64 / 20.0);
        // the base's support balances the block's top edge
        assert!((v[2] + v[6]).abs() < 1e-8 * v[3].abs(), "{row:?}");
        assert!((v[3] + v[5]).abs() < 1e-8 * v[3].abs(), "{row:?}");
        assert!(v[3] > 0.0, "{row:?}");
    }
}
