//! The meshes a host registers once ([`MeshHandle`]s): a generational
//! table, so a handle used after its mesh was removed is an error
//! (E0601), never another mesh.

use super::EmbedError;
use crate::scene::Mesh;
use std::sync::Arc;

/// A mesh registered with [`super::StyleRuntime::add_mesh`]. Copy it into
/// as many [`super::Instance`]s as you like; it stays valid until
/// [`super::StyleRuntime::remove_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MeshHandle {
    pub(super) index: u32,
    /// Bumped each time the slot is reused, so an old handle never names a new mesh.
    pub(super) generation: u32,
    /// Which runtime gave it out (a handle of another runtime is refused).
    pub(super) runtime: u32,
}

/// One slot of the table: the mesh it holds (if any) and its generation.
#[derive(Default)]
struct Slot {
    mesh: Option<Arc<Mesh>>,
    generation: u32,
}

/// The registered meshes.
pub(super) struct MeshTable {
    runtime: u32,
    slots: Vec<Slot>,
    /// Bumped by every add and remove: the set of meshes changed.
    pub revision: u64,
}

impl MeshTable {
    pub fn new(runtime: u32) -> MeshTable {
        MeshTable {
            runtime,
            slots: Vec::new(),
            revision: 0,
        }
    }

    pub fn add(&mut self, mesh: Arc<Mesh>) -> MeshHandle {
        self.revision += 1;
        let index = match self.slots.iter().position(|s| s.mesh.is_none()) {
            Some(free) => free,
            None => {
                self.slots.push(Slot::default());
                self.slots.len() - 1
            }
        };
        let slot = &mut self.slots[index];
        slot.generation += 1;
        slot.mesh = Some(mesh);
        MeshHandle {
            index: index as u32,
            generation: slot.generation,
            runtime: self.runtime,
        }
    }

    pub fn remove(&mut self, handle: MeshHandle) -> Result<Arc<Mesh>, EmbedError> {
        self.get(handle)?;
        self.revision += 1;
        self.slots[handle.index as usize]
            .mesh
            .take()
            .ok_or(EmbedError::UnknownMesh(handle))
    }

    /// How many meshes are registered (not removed).
    pub fn len(&self) -> usize {
        self.slots.iter().filter(|s| s.mesh.is_some()).count()
    }

    pub fn get(&self, handle: MeshHandle) -> Result<&Arc<Mesh>, EmbedError> {
        if handle.runtime != self.runtime {
            return Err(EmbedError::UnknownMesh(handle));
        }
        match self.slots.get(handle.index as usize) {
            Some(Slot {
                mesh: Some(mesh),
                generation,
            }) if *generation == handle.generation => Ok(mesh),
            _ => Err(EmbedError::UnknownMesh(handle)),
        }
    }
}
