use super::*;

fn settings() -> EngineSettings {
    arm_settings()
}

fn free_rotor_module() -> ModuleParams {
    let mut m = ModuleParams::thesis_joint();
    m.drive = m.drive.elastic();
    m
}

#[test]
fn bad_input_is_named() {
    let good = vec![free_rotor_module()];
    let drive = LinearDrives::try_new(&[(100.0, 1e4, 0.0)]).unwrap();
    let arm = |m: &[ModuleParams], g: [f64; 3]| {
        EngineArm::try_new(m, g, RotorBody::default(), drive.clone(), settings()).err()
    };
    assert!(matches!(
        arm(&[], [0.0; 3]),
        Some(ParamError::NotPositive {
            name: "modules",
            ..
        })
    ));
    assert!(matches!(
        arm(&good, [0.0, f64::NAN, 0.0]),
        Some(ParamError::NotFinite {
            name: "gravity",
            ..
        })
    ));
    let mut bad = good.clone();
    bad[0].axis = [0.0, 0.0, 2.0];
    assert!(matches!(
        arm(&bad, [0.0; 3]),
        Some(ParamError::OutOfRange { name: "axis", .. })
    ));
    let mut bad = good.clone();
    bad[0].link_locked = true;
    assert!(matches!(
        arm(&bad, [0.0; 3]),
        Some(ParamError::OutOfRange {
            name: "link_locked",
            ..
        })
    ));
    // A carrying link lighter than the rotor it carries.
    let mut bad = vec![free_rotor_module(), free_rotor_module()];
    bad[0].link_mass = 0.05;
    assert!(matches!(
        arm(&bad, [0.0; 3]),
        Some(ParamError::OutOfRange {
            name: "link_mass",
            ..
        })
    ));
    // A link whose inertia turns negative once the rotor is taken out.
    let mut bad = vec![free_rotor_module(), free_rotor_module()];
    bad[0].link_inertia = [[1e-6, 0.0, 0.0], [0.0, 1e-6, 0.0], [0.0, 0.0, 1e-6]];
    bad[0].link_com = [0.45, 0.0, 0.0];
    assert!(matches!(
        arm(&bad, [0.0; 3]),
        Some(ParamError::Negative {
            name: "link_inertia",
            ..
        })
    ));
    let mut bad = good.clone();
    bad[0].link_inertia[0][1] = 1e-3;
    assert!(matches!(
        arm(&bad, [0.0; 3]),
        Some(ParamError::OutOfRange {
            name: "link_inertia",
            ..
        })
    ));
    assert!(matches!(
        RotorBody::try_new(0.1, -1.0),
        Err(ParamError::NotPositive {
            name: "rotor_transverse_inertia",
            ..
        })
    ));
    assert!(matches!(
        LinearDrives::try_new(&[(100.0, 1e4, -1.0)]),
        Err(ParamError::Negative {
            name: "damping",
            ..
        })
    ));
}

/// One module, no gravity, a constant motor torque: the drive's
/// torques cancel in `J_l q̇_l + N I_m q̇_m` (eq. 4.1 plus N × eq. 4.2),
/// which grows as `N τ_m t`, whatever the drive does. `J_l` is the
/// link's moment about the joint axis by hand: the rod's
/// `m l²/12 + m (l/2)²`.
#[test]
fn motor_torque_feeds_the_momentum_of_link_and_rotor() {
    let m = free_rotor_module();
    let (mass, l, im, n) = (0.64, 0.45, 1.14e-5, 100.0);
    let j_l = mass * l * l / 12.0 + mass * (l / 2.0) * (l / 2.0);
    let drive = LinearDrives::try_new(&[(n, 1e4, 0.0)]).unwrap();
    let mut arm =
        EngineArm::try_new(&[m], [0.0; 3], RotorBody::default(), drive, settings()).unwrap();
    let tau = 0.05;
    arm.set_motor_torque(&[tau]);
    arm.run(0.2);
    let s = arm.drive_states()[0];
    let momentum = j_l * s.link_speed + n * im * s.motor_speed;
    let want = n * tau * arm.time();
    assert!(
        (momentum - want).abs() < 1e-9 * want,
        "{momentum} vs {want}"
    );
    // The drive did twist and oscillate: the check is not trivial.
    assert!(s.link_speed.abs() > 0.1 && arm.energy() > 0.0);
}

/// Set state is read back as set (angles from the poses, speeds from
/// the engine's joint velocities), with two modules on different axes.
#[test]
fn state_reads_back() {
    let mut b = free_rotor_module();
    b.axis = [0.0, 1.0, 0.0];
    b.origin = [0.45, 0.0, 0.0];
    let modules = [free_rotor_module(), b];
    let drive = LinearDrives::try_new(&[(100.0, 1e4, 0.0), (100.0, 1e4, 0.0)]).unwrap();
    let mut arm =
        EngineArm::try_new(&modules, [0.0; 3], RotorBody::default(), drive, settings()).unwrap();
    arm.set_state(&[0.3, -1.2], &[30.0, -120.0], &[0.5, -0.25], &[50.0, -25.0]);
    arm.read_state();
    let s = arm.drive_states();
    for (got, want) in [
        (s[0].link_angle, 0.3),
        (s[1].link_angle, -1.2),
        (s[0].motor_angle, 30.0),
        (s[1].motor_angle, -120.0),
        (s[0].link_speed, 0.5),
        (s[1].motor_speed, -25.0),
    ] {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}

/// A drive hook that returns NaN leaves the state finite (its torques are
/// applied as zero: the link then falls freely under gravity).
#[test]
fn non_finite_drive_torque_is_not_propagated() {
    let mut m = free_rotor_module();
    m.axis = [0.0, 1.0, 0.0];
    let hook = |_: usize, _: &DriveState| DriveTorques {
        transmission: f64::NAN,
        on_link: f64::INFINITY,
        on_motor: f64::NAN,
    };
    let mut arm = EngineArm::try_new(
        &[m],
        [0.0, 0.0, -9.81],
        RotorBody::default(),
        hook,
        settings(),
    )
    .unwrap();
    arm.set_motor_torque(&[f64::NAN]);
    arm.run(0.05);
    let s = arm.drive_states()[0];
    assert!(s.link_angle.is_finite() && s.motor_speed.is_finite());
    assert!(arm.drive_torques()[0].transmission == 0.0);
    // It moved: gravity acts on the horizontal link.
    assert!(s.link_angle.abs() > 1e-3, "{}", s.link_angle);
}
