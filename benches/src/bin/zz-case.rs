use bw_models::Settings;
use bwc_benches::stress::{run_with, sample, settings};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let i: u64 = a[1].parse().unwrap();
    let rtol: f64 = a[2].parse().unwrap();
    let c = sample(1, i);
    println!("{:?}", c);
    let s = Settings {
        rtol,
        atol: rtol / 100.0,
        ..settings()
    };
    let o = run_with(&c, &s);
    println!("{:?} {:?} series {}", o.class, o.result, o.series);
}
