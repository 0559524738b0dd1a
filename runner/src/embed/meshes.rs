//! The meshes a host registers once ([`MeshHandle`]s): a generational
//! table, so a handle used after its mesh was removed is an error
//! (E0601), never another mesh. A mesh may come with what the renderer
//! draws beyond its vertices ([`MeshExtras`]): the time-varying primitive
//! it is the geometry of (the ocean), the patch of a patched surface it
//! is (with its blended n-ring), or the rig a host's poses deform.

use super::EmbedError;
use crate::scene::patch_blend::PatchBlend;
use crate::scene::patches::PatchOf;
use crate::scene::rig::Rig;
use crate::scene::{Mesh, Primitive};
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

/// What a registered mesh carries besides its vertices, as a scene's
/// [`crate::scene::Object`] does: every instance of the mesh gets it.
#[derive(Debug, Clone, Default)]
pub(super) struct MeshExtras {
    /// The primitive whose geometry at t = 0 the mesh is, rebuilt at each
    /// frame's time (`Object::time_varying`).
    pub time_varying: Option<Primitive>,
    /// The patch's faces and n-ring with its weights (`Object::blend`).
    pub blend: Option<Arc<PatchBlend>>,
    /// Which patch of which surface the mesh is (`Object::patch`).
    pub patch: Option<PatchOf>,
    /// A skinned or morphing mesh's rig, which its instances' poses deform
    /// (`StyleRuntime::add_skinned_mesh`; `Object::pose`).
    pub rig: Option<Arc<Rig>>,
}

/// A registered mesh and its extras.
#[derive(Debug, Clone)]
pub(super) struct Entry {
    pub mesh: Arc<Mesh>,
    pub extras: MeshExtras,
}

/// One slot of the table: the mesh it holds (if any) and its generation.
#[derive(Default)]
struct Slot {
    entry: Option<Entry>,
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

    pub fn add(&mut self, mesh: Arc<Mesh>, extras: MeshExtras) -> MeshHandle {
        self.revision += 1;
        let index = match self.slots.iter().position(|s| s.entry.is_none()) {
            Some(free) => free,
            None => {
                self.slots.push(Slot::default());
                self.slots.len() - 1
            }
        };
        let slot = &mut self.slots[index];
        slot.generation += 1;
        slot.entry = Some(Entry { mesh, extras });
        MeshHandle {
            index: index as u32,
            generation: slot.generation,
            runtime: self.runtime,
        }
    }

    pub fn remove(&mut self, handle: MeshHandle) -> Result<Entry, EmbedError> {
        self.entry(handle)?;
        self.revision += 1;
        self.slots[handle.index as usize]
            .entry
            .take()
            .ok_or(EmbedError::UnknownMesh(handle))
    }

    /// Put `new` in the place of `old` (a deformed copy: same topology) in
    /// every entry holding it (handles of one shared mesh are one mesh),
    /// keeping their extras. Not a change of the set of meshes: `revision`
    /// stays, so the scene is not made anew.
    pub fn replace(&mut self, old: &Arc<Mesh>, new: &Arc<Mesh>) {
        for entry in self.slots.iter_mut().filter_map(|s| s.entry.as_mut()) {
            if Arc::ptr_eq(&entry.mesh, old) {
                entry.mesh = new.clone();
            }
        }
    }

    /// How many meshes are registered (not removed).
    pub fn len(&self) -> usize {
        self.slots.iter().filter(|s| s.entry.is_some()).count()
    }

    pub fn get(&self, handle: MeshHandle) -> Result<&Arc<Mesh>, EmbedError> {
        self.entry(handle).map(|e| &e.mesh)
    }

    /// The mesh `handle` names, with its extras.
    pub fn entry(&self, handle: MeshHandle) -> Result<&Entry, EmbedError> {
        if handle.runtime != self.runtime {
            return Err(EmbedError::UnknownMesh(handle));
        }
        match self.slots.get(handle.index as usize) {
            Some(Slot {
                entry: Some(entry),
                generation,
            }) if *generation == handle.generation => Ok(entry),
            _ => Err(EmbedError::UnknownMesh(handle)),
        }
    }
}
