use trajkit::otg::*;
#[test]
fn scratch() {
    let mut inp = InputParameter::<3>::new();
    inp.current_position = [-2.6717951790162617, -2.277891812199905, 2.9946440309405844];
    inp.current_velocity = [-0.020476298186567543, -0.8757237275622343, 0.1649482212389593];
    inp.current_acceleration = [-0.4271476103495482, 1.5672346031662094, 0.3784526473305734];
    inp.target_position = [-4.292069204010286, 3.044560859435105, 4.818436679369842];
    inp.target_velocity = [-0.10604874157112404, -0.006342522392738914, 0.13071076560213535];
    inp.target_acceleration = [-0.185434498429089, 2.7682158831043058, -0.6203123573982929];
    inp.max_velocity = [0.1636411138550431, 0.9699166420666886, 0.3019130141428394];
    inp.max_acceleration = [2.306564134952294, 5.236364187267679, 4.36496492506666];
    inp.max_jerk = [0.9187905772684299, 16.14183168164987, 1.720834162266587];
    inp.options.control_interface = ControlInterface::Velocity;
    let otg = Otg::<3>::new(0.001);
    let tr = otg.calculate(&inp).unwrap();
    let mut m = [0.0; 3];
    tr.independent_min_durations(&mut m);
    eprintln!("dur {} indep {:?}", tr.duration(), m);
    for i in 0..3 {
        let mut d = inp;
        d.enabled = [false; 3];
        d.enabled[i] = true;
        d.options.minimum_duration = Some(1.0424795196234393);
        eprintln!("dof {i}: {:?}", otg.calculate(&d).map(|t| t.duration()));
    }
}
