//! Every registered operator (`npr_stdlib::ops::ALL`) on the GPU (lavapipe
//! here) against its f64 reference, over its data cases: each call is built
//! from the operator's signature and the case's arguments by
//! `harness::cases`, so a new operator needs no hand-written GPU test.

mod harness;

#[test]
fn every_operator_matches_its_reference_on_its_cases() {
    let (mut cases, mut calls) = (0, 0);
    for def in npr_stdlib::ops::ALL {
        for (i, case) in def.cases.iter().enumerate() {
            calls += harness::cases::run_case(def, i, case);
            cases += 1;
        }
    }
    println!(
        "{} operators, {cases} cases, {calls} calls compared",
        npr_stdlib::ops::ALL.len()
    );
}
