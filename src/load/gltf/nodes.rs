//! The node tree of one glTF scene flattened into placements: each node
//! that carries a mesh gives one (mesh, world-from-mesh) pair, so a mesh
//! used by several nodes is built once and instanced. Matrices are glTF's
//! column-major `matrix`, or `T·R·S` from the node's translation, rotation
//! (unit quaternion) and scale (glTF 2.0 §3.5.3), composed root to leaf.
//!
//! A valid glTF node tree is a forest (each node has at most one parent):
//! a node reached twice is a cycle or a shared child, and an error naming
//! it; the walk is iterative and visits each node once, so a deep or
//! cyclic tree cannot overflow the stack or loop.

use glam::Mat4;
use gltf::Document;

/// A mesh placed by a node.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    /// Index in the document's meshes.
    pub mesh: usize,
    /// Index of the node that places it (for messages).
    pub node: usize,
    /// The node's world transform (the asset's own space, before the
    /// object's `transform`).
    pub world_from_mesh: Mat4,
    /// The skin that moves the mesh's vertices, if the node has one.
    pub skin: Option<usize>,
}

/// A `KHR_lights_punctual` light placed by a node.
#[derive(Clone, Copy, Debug)]
pub struct LightPlacement {
    /// Index in the document's lights.
    pub light: usize,
    /// Index of the node that places it.
    pub node: usize,
    /// The node's world transform (the asset's own space).
    pub world: Mat4,
}

/// A camera placed by a node.
#[derive(Clone, Copy, Debug)]
pub struct CameraPlacement {
    /// Index in the document's cameras.
    pub camera: usize,
    /// Index of the node that places it.
    pub node: usize,
    /// The node's world transform (the asset's own space).
    pub world: Mat4,
}

/// What one walk of a scene's node tree places.
#[derive(Debug, Default)]
pub struct Walk {
    /// Meshes, by node in document order.
    pub meshes: Vec<Placement>,
    /// `KHR_lights_punctual` lights, by node in document order.
    pub lights: Vec<LightPlacement>,
    /// Cameras, by node in document order.
    pub cameras: Vec<CameraPlacement>,
}

/// The placements of scene `scene` (default: the file's `scene`, else 0),
/// each node placed by `locals` (every node's local transform, document
/// order: the node's own, or posed by an animation).
pub fn flatten(doc: &Document, scene: Option<u32>, locals: &[Mat4]) -> Result<Vec<Placement>, String> {
    walk(doc, scene, locals).map(|w| w.meshes)
}

/// [`flatten`], with the scene's lights and cameras placed by the same walk.
pub fn walk(doc: &Document, scene: Option<u32>, locals: &[Mat4]) -> Result<Walk, String> {
    let count = doc.scenes().count();
    let chosen = match scene {
        Some(s) => doc
            .scenes()
            .nth(s as usize)
            .ok_or_else(|| format!("the asset has {count} scene(s); there is no scene {s}"))?,
        None => match doc.default_scene().or_else(|| doc.scenes().next()) {
            Some(s) => s,
            None => return Err("the asset has no scene to place".into()),
        },
    };
    let mut seen = vec![false; doc.nodes().count()];
    let mut out = Vec::new();
    let mut lights = Vec::new();
    let mut cameras = Vec::new();
    let mut stack: Vec<(gltf::Node, Mat4)> = chosen.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        let i = node.index();
        match seen.get_mut(i) {
            Some(s) if !*s => *s = true,
            _ => {
                return Err(format!(
                    "nodes[{i}] is reached twice: the node tree has a cycle or a node with two parents"
                ));
            }
        }
        let local = locals.get(i).copied().unwrap_or(Mat4::NAN);
        if !local.is_finite() {
            return Err(format!("nodes[{i}]: its transform is not finite"));
        }
        let world = parent * local;
        let light = node.light();
        // Only a node that places something needs a finite world transform.
        if (node.mesh().is_some() || light.is_some() || node.camera().is_some()) && !world.is_finite() {
            return Err(format!("nodes[{i}]: its world transform is not finite"));
        }
        if let Some(m) = node.mesh() {
            // A node scaled to nothing is placed all the same (the caller
            // leaves it out of the picture): an animation may scale it
            // back, and placements keep one order whatever the pose.
            out.push(Placement {
                mesh: m.index(),
                node: i,
                world_from_mesh: world,
                skin: node.skin().map(|s| s.index()),
            });
        }
        if let Some(l) = light {
            lights.push(LightPlacement {
                light: l.index(),
                node: i,
                world,
            });
        }
        if let Some(c) = node.camera() {
            cameras.push(CameraPlacement {
                camera: c.index(),
                node: i,
                world,
            });
        }
        stack.extend(node.children().map(|c| (c, world)));
    }
    // Document order of nodes, so object ids, lights and notes are stable.
    out.sort_by_key(|p| p.node);
    lights.sort_by_key(|l| l.node);
    cameras.sort_by_key(|c| c.node);
    Ok(Walk {
        meshes: out,
        lights,
        cameras,
    })
}

/// Every node's world transform under `locals`, whatever scene holds it
/// (a skin's joints need not be placed by the scene): each node's parent
/// chain composed root to leaf, each node once (a long chain costs its
/// length, not its square). A node with two parents, or in a cycle, is
/// an error.
pub fn worlds(doc: &Document, locals: &[Mat4]) -> Result<Vec<Mat4>, String> {
    let count = doc.nodes().count();
    let mut parent: Vec<Option<usize>> = vec![None; count];
    for n in doc.nodes() {
        for c in n.children() {
            let slot = parent
                .get_mut(c.index())
                .ok_or_else(|| format!("nodes[{}] names a child that does not exist", n.index()))?;
            if slot.replace(n.index()).is_some() {
                return Err(format!("nodes[{}] has two parents", c.index()));
            }
        }
    }
    let local = |i: usize| locals.get(i).copied().unwrap_or(Mat4::NAN);
    let mut world: Vec<Option<Mat4>> = vec![None; count];
    let mut chain = Vec::new();
    for i in 0..count {
        // Up to the first node already placed (or a root), then down.
        chain.clear();
        let mut at = Some(i);
        while let Some(n) = at.filter(|&n| world[n].is_none()) {
            if chain.len() > count {
                return Err(format!("nodes[{i}] is in a cycle of the node tree"));
            }
            chain.push(n);
            at = parent[n];
        }
        let mut m = at.and_then(|n| world[n]).unwrap_or(Mat4::IDENTITY);
        for &n in chain.iter().rev() {
            m *= local(n);
            world[n] = Some(m);
        }
    }
    world
        .into_iter()
        .enumerate()
        .map(|(i, m)| {
            m.filter(Mat4::is_finite)
                .ok_or_else(|| format!("nodes[{i}]: its world transform is not finite"))
        })
        .collect()
}
