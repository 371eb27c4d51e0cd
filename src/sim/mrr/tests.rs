use super::*;

fn three_modules() -> Vec<ModuleParams> {
    let mut a = ModuleParams::thesis_joint();
    a.axis = [0.0, 0.0, 1.0];
    let mut b = ModuleParams::thesis_joint();
    b.axis = misaligned([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 0.05);
    b.origin = [0.45, 0.0, 0.0];
    b.link_mass = 1.2;
    let mut c = ModuleParams::thesis_joint();
    c.axis = [0.0, 1.0, 0.0];
    c.origin = [0.45, 0.0, 0.0];
    vec![a, b, c]
}

/// The RNEA inertia matrix is symmetric positive definite, and the
/// motor-row entries are the couplings of eq. (4.4)/(4.6):
/// `M[m_i, l_j] = I_mi z_miᵀ z_lj` for the links j < i below the rotor.
#[test]
fn inertia_matrix_has_the_couplings_of_eq_4_6() {
    let mut r = Mrr::try_new(three_modules(), [0.0, 0.0, -9.81], 1e-3, 1, 0).unwrap();
    r.set_state(&[0.3, -0.7, 1.1], &[0.0; 3], &[0.0; 3], &[0.0; 3]);
    let m = r.inertia_matrix();
    let dim = 6;
    for i in 0..dim {
        for j in 0..dim {
            assert!((m[i * dim + j] - m[j * dim + i]).abs() < 1e-12);
        }
    }
    let k = r.kinematics(r.link_angles());
    for i in 0..3 {
        for j in 0..3 {
            let want = if j < i {
                r.modules[i].rotor_inertia * dot(k.axis[i], k.axis[j])
            } else {
                0.0
            };
            assert!((m[(3 + i) * dim + j] - want).abs() < 1e-15, "{i},{j}");
        }
        assert!((m[(3 + i) * dim + 3 + i] - r.modules[i].rotor_inertia).abs() < 1e-18);
    }
    let mut a = m.clone();
    let mut b = vec![1.0; dim];
    solve_spd(&mut a, &mut b, dim);
    assert!(b.iter().all(|v| v.is_finite()));
}

/// The kinetic energy from the velocities equals ½ vᵀ M v (the RNEA
/// matrix and the independent energy expression agree).
#[test]
fn kinetic_energy_is_quadratic_form_of_inertia_matrix() {
    let mut r = Mrr::try_new(three_modules(), [0.0; 3], 1e-3, 1, 0).unwrap();
    for m in r.modules.iter_mut() {
        m.drive = m.drive.elastic();
    }
    let v = [0.4, -1.3, 2.0, 30.0, -80.0, 55.0];
    r.set_state(&[0.2, 0.5, -0.4], &[20.0, 50.0, -40.0], &v[..3], &v[3..]);
    // Elastic energy at this state, removed to leave the kinetic part.
    let mut e_el = 0.0;
    for i in 0..3 {
        let (d, _, _) = r.modules[i]
            .drive
            .compliance_torsion(r.link_angles()[i], r.motor_angles()[i]);
        e_el += r.modules[i].drive.elastic_energy(d, &[]);
    }
    let kinetic = r.energy() - e_el;
    let m = r.inertia_matrix();
    let mut quad = 0.0;
    for i in 0..6 {
        for j in 0..6 {
            quad += 0.5 * v[i] * m[i * 6 + j] * v[j];
        }
    }
    assert!(
        (kinetic - quad).abs() < 1e-12 * quad.abs(),
        "{kinetic} vs {quad}"
    );
}

/// A payload at 0.4 m on a horizontal link adds `m g 0.4` to the
/// magnitude of the holding torque (the thesis's payload experiment, Fig. 3.5b), and its
/// inertia about the joint axis adds `m 0.4²`.
#[test]
fn payload_adds_its_gravity_torque_and_inertia() {
    let mut j = ModuleParams::thesis_joint();
    j.axis = [0.0, 1.0, 0.0];
    let r0 = Mrr::try_new(vec![j.clone()], [0.0, 0.0, -9.81], 1e-3, 1, 0).unwrap();
    let r1 = Mrr::try_new(
        vec![j.with_payload(0.5, [0.4, 0.0, 0.0])],
        [0.0, 0.0, -9.81],
        1e-3,
        1,
        0,
    )
    .unwrap();
    let dg = r1.gravity_torques()[0] - r0.gravity_torques()[0];
    // Gravity's moment about +y is (x,0,0) × (0,0,−mg) = +mgx, so the
    // holding torque is −mgx.
    assert!((dg + 0.5 * 9.81 * 0.4).abs() < 1e-12, "{dg}");
    let di = r1.inertia_matrix()[0] - r0.inertia_matrix()[0];
    assert!((di - 0.5 * 0.16).abs() < 1e-12, "{di}");
}

/// The motor angles returned for a torque make the drive carry it.
#[test]
fn motor_angles_for_torque_round_trip() {
    let r = Mrr::try_new(three_modules(), [0.0; 3], 1e-3, 1, 0).unwrap();
    let q_l = [0.3, -1.0, 2.0];
    let want = [5.0, -2.0, 0.5];
    let q_m = r.motor_angles_for_torque(&q_l, &want);
    let mut r2 = r.clone();
    r2.set_state(&q_l, &q_m, &[0.0; 3], &[0.0; 3]);
    for (t, w) in r2.transmission_torques().iter().zip(want) {
        assert!((t - w).abs() < 1e-9, "{t} vs {w}");
    }
}

#[test]
fn bad_parameters_are_rejected_by_name() {
    let ok = || vec![ModuleParams::thesis_joint()];
    let g = [0.0, 0.0, -9.81];
    let e = Mrr::try_new(ok(), g, 5e-3, 10, 0).unwrap_err();
    assert!(matches!(
        e,
        ParamError::OutOfRange {
            name: "control_period",
            ..
        }
    ));
    let e = Mrr::try_new(ok(), g, 1e-3, 0, 0).unwrap_err();
    assert!(matches!(
        e,
        ParamError::NotPositive {
            name: "steps_per_period",
            ..
        }
    ));
    let mut m = ok();
    m[0].axis = [0.0, 0.0, 2.0];
    let e = Mrr::try_new(m, g, 1e-3, 10, 0).unwrap_err();
    assert!(matches!(e, ParamError::OutOfRange { name: "axis", .. }));
    let mut m = ok();
    m[0].rotor_inertia = f64::NAN;
    let e = Mrr::try_new(m, g, 1e-3, 10, 0).unwrap_err();
    assert!(matches!(
        e,
        ParamError::NotFinite {
            name: "rotor_inertia",
            ..
        }
    ));
    let e = Mrr::try_new(ok(), [0.0, f64::INFINITY, 0.0], 1e-3, 10, 0).unwrap_err();
    assert!(matches!(
        e,
        ParamError::NotFinite {
            name: "gravity",
            ..
        }
    ));
}
