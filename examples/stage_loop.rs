//! Runs one `impactd bench` stage a fixed number of times (for instruction-count profilers).
//! Usage: `stage_loop NAME [N]`.

#![allow(clippy::unwrap_used)]

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().expect("usage: stage_loop NAME [N]");
    let n: usize = args.next().map_or(1000, |s| s.parse().expect("N"));
    let mut stage = impactd::stages::all_stages().into_iter().find(|s| s.name == name).expect("no such stage");
    let mut acc = 0.0;
    for i in 0..n {
        acc += std::hint::black_box((stage.run)(i));
    }
    println!("{name}: {n} runs, checksum {acc}");
}
