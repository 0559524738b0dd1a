//! Run-time lines (Klein et al. 2000, §5): feature edges of the scene's
//! meshes ([`edges`]: creases once per mesh, silhouettes per eye, chains) and
//! the wavy screen-space strips drawn along them ([`strip`]). Both on the
//! CPU in f64; see the module headers for why. [`cache`] keeps what is
//! static per mesh and rebuilds an eye's strips only when its view changes.
//! [`objects`] says which surfaces a pass draws (a patched object's patches
//! as its whole mesh). [`intersections`] finds where surfaces pass through
//! each other, and [`sets`] builds a pass's line sets (decision 0056): each
//! set's edge types, one owner per edge by priority, its own style.
//! [`visibility`] counts the surfaces in front of each piece of a set's
//! lines (quantitative invisibility, decision 0063).

pub mod cache;
pub mod draw;
pub mod edges;
pub mod intersections;
pub mod objects;
pub mod sets;
pub mod strip;
pub mod viewpoint;
pub mod visibility;
