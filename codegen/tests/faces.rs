//! Formulations of 3D faces through the generator: every shipped face
//! formulation parses, derives and lowers; the kernels take `xi_s` and
//! `xi_m` as slices; the projection is in closed form exactly when the
//! master is a tri3.

use std::path::Path;

fn face_sources() -> Vec<codegen::Source> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../contact-kernels/formulations");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("formulations directory")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| codegen::Source {
            name: p.file_stem().unwrap().to_str().unwrap().to_owned(),
            text: std::fs::read_to_string(p).unwrap(),
            compiled: true,
        })
        .filter(|s| {
            codegen::Formulation::parse(&s.name, &s.text)
                .unwrap()
                .signature
                .dim()
                == 3
        })
        .collect()
}

#[test]
fn face_formulations_generate_with_closed_form_on_tri3_masters() {
    let sources = face_sources();
    assert_eq!(sources.len(), 8);
    let plan = codegen::KernelPlan::build(&sources).unwrap();
    for f in &plan.formulations {
        let set = f.kernels.as_ref().unwrap();
        // `<slave>-<reading>` or `<slave>-<master>-<reading>`.
        let kinds: Vec<&str> = f
            .name
            .split('-')
            .filter(|w| *w == "tri3" || *w == "quad4")
            .collect();
        let master_tri3 = *kinds.last().unwrap() == "tri3";
        assert_eq!(set.closed_form_projection, master_tri3, "{}", f.name);
        let sig = &set.signature;
        assert_eq!(sig.dim(), 3);
        assert_eq!(sig.implicit_len(), 2);
        for k in &set.kernels {
            eprintln!("{:28} {:24} {}", f.name, k.name, k.ops);
        }
    }
}
