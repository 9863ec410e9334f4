use trajkit::otg::*;
#[test]
fn scratch() {
    let mut inp = InputParameter::<3>::new();
    inp.current_position = [-2.76902150348738, -0.6380898908203321, 2.516132355242913];
    inp.target_position = [2.930767915123262, 4.796309661329877, -1.8223087747448883];
    inp.max_velocity = [0.2976403387648034, 0.10326750523262641, 0.19850042934736603];
    inp.max_acceleration = [0.10505563691575763, 2.2710337351123058, 1.2567797204396784];
    inp.max_jerk = [50.849078668184525, 32.84195481436607, 2.591139357503843];
    let otg = Otg::<3>::new(0.001);
    let tr = otg.calculate(&inp).unwrap();
    let mut m = [0.0; 3];
    tr.independent_min_durations(&mut m);
    eprintln!("dur {} indep {:?}", tr.duration(), m);
    for i in 0..3 {
        let mut d = inp;
        d.enabled = [false; 3];
        d.enabled[i] = true;
        d.options.minimum_duration = Some(52.736637133635405);
        eprintln!("dof {i}: {:?}", otg.calculate(&d).map(|t| t.duration()));
    }
}
