//! Soundness of the interval arithmetic: random expressions evaluated in
//! f32 at random points inside their inputs' intervals always land inside
//! the interval the analysis computes.
