//! Tests of the one-call wrist step.

use super::*;

#[test]
fn table_6_1_is_valid() {
    let p = WristStepParams::table_6_1().unwrap();
    assert_eq!(p.sample_period(), 0.004);
}
