//! The committed `-sweep` experiments, written with the sweep grammar (catalog::sweep),
//! describe exactly the runs their hand-expanded form (one block per value, as the files were
//! written before the grammar; kept in tests/fixtures/) described: same keys, same order, every
//! field of every Job equal.

#[test]
fn sweep_experiments_expand_to_the_hand_written_runs() {
    let root = catalog::root_from_current_dir().unwrap();
    let files = catalog::load_dir(&root.join("experiments")).unwrap();
    let committed: Vec<String> = files
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .filter(|j| j.experiment.ends_with("-sweep"))
        .map(|j| format!("{j:?}"))
        .collect();
    let fixtures = [
        include_str!("fixtures/hand-expanded-jia2019.toml"),
        include_str!("fixtures/hand-expanded-kong2019.toml"),
        include_str!("fixtures/hand-expanded-zhang2018.toml"),
    ];
    let mut hand: Vec<String> = Vec::new();
    for text in fixtures {
        let file = catalog::PaperFile::from_toml(text).unwrap();
        hand.extend(file.jobs().unwrap().iter().map(|j| format!("{j:?}")));
    }
    // The committed files order papers by file name, as the fixtures are listed.
    assert_eq!(committed.len(), 18 + 10 + 8 + 3, "runs of the four sweeps");
    assert_eq!(committed.len(), hand.len());
    for (c, h) in committed.iter().zip(&hand) {
        assert_eq!(c, h);
    }
}
