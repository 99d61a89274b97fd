//! A tour of gym-core's spaces: build, sample with a seed, check membership, flatten.
//!
//! Run with `cargo run -p examples --example spaces_tour`.

use gym_core::{
    AnySpace, BoxSpace, DictSpace, Discrete, MultiBinary, Space, flatdim, flatten, flatten_space,
    rng_from_seed, unflatten,
};

fn main() -> Result<(), gym_core::SpaceError> {
    let space = DictSpace::new([
        (
            "position",
            AnySpace::from(BoxSpace::<f32>::uniform(-1.0, 1.0, &[3])?),
        ),
        ("gear", AnySpace::from(Discrete::new(4)?)),
        ("switches", AnySpace::from(MultiBinary::new(&[2])?)),
    ])?;
    println!("space:        {}", AnySpace::from(space.clone()));
    let mut rng = rng_from_seed(42);
    let x = space.sample(&mut rng);
    println!("sample:       {x:?}");
    println!("contains:     {}", space.contains(&x));
    let flat = flatten(&space, &x)?;
    println!("flatdim:      {} ({})", flatdim(&space), flat.dtype());
    println!("flattened:    {:?}", flat.to_f64_vec());
    println!("flat space:   {}", flatten_space(&space));
    println!("round trip:   {}", unflatten(&space, &flat)? == x);
    Ok(())
}
