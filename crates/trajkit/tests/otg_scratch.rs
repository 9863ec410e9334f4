use rsruckig::prelude::*;
#[test]
fn scratch() {
    let cases: [[f64; 9]; 3] = [
        [-0.6312404900629707, 0.8559616990797103, 0.5391354872130796, -0.21031707846501035, -1.5082982170034822, -0.14409780214669476, 1.6067548482236833, 3.868887185054934, 0.5149685138462994],
        [3.1617610514694103, 0.9019010239266334, -0.4348590055947338, 3.026923795659206, -0.6377298880875794, -0.06344713802825752, 1.5915612384041398, 1.1001623891043801, 0.2728896822324516],
        [1.56235529232191, 3.9527954278916555, -1.8317272707976247, 3.689089421239032, 1.4697930047801844, 0.17771165023849678, 2.912194682399952, 2.608305763158582, 0.5117779904015314],
    ];
    for c in cases {
        let mut otg = Ruckig::<1, IgnoreErrorHandler>::new(None, 0.001);
        let mut ri = InputParameter::<1>::new(None);
        ri.current_position[0] = c[0]; ri.current_velocity[0] = c[1]; ri.current_acceleration[0] = c[2];
        ri.target_position[0] = c[3]; ri.target_velocity[0] = c[4]; ri.target_acceleration[0] = c[5];
        ri.max_velocity[0] = c[6]; ri.max_acceleration[0] = c[7]; ri.max_jerk[0] = c[8];
        let mut tr = Trajectory::<1>::new(None);
        let _ = otg.calculate(&ri, &mut tr);
        let p = &tr.profiles[0][0];
        eprintln!("T {} t {:?}\n j {:?}\n a {:?}\n v {:?} brake {:?}", tr.duration, p.t, p.j, p.a, p.v, p.brake);
        let d = trajkit::otg::Dof1 { p0: c[0], v0: c[1], a0: c[2], pf: c[3], vf: c[4], af: c[5], vmax: c[6], vmin: -c[6], amax: c[7], amin: -c[7], jmax: c[8], interface: trajkit::otg::ControlInterface::Position };
        let pr = trajkit::otg::time_optimal(&d).unwrap();
        for k in 0..pr.segments() { eprintln!("  ours {:?}", pr.segment(k)); }
    }
}
