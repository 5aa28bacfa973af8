//! The flattened node: 32 bytes, so two share a 64-byte cache line and a
//! node never straddles one. Nodes are stored depth-first: an interior
//! node's first child is the next node, the second is found by offset
//! (pbrt's `LinearBVHNode`, <https://pbr-book.org/4ed/Primitives_and_Intersection_Acceleration/Bounding_Volume_Hierarchies>).

use glam::Vec3A;

use crate::accel::Aabb;
use crate::accel::aabb::slab;

#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct Node {
    pub min: [f32; 3],
    /// Interior: index of the second child. Leaf: first slot in the
    /// primitive index array.
    pub offset: u32,
    pub max: [f32; 3],
    /// Number of primitives; 0 marks an interior node.
    pub count: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 32);

impl Node {
    #[inline]
    pub fn leaf(b: Aabb, first: u32, count: u32) -> Self {
        debug_assert!(count > 0, "a leaf holds at least one primitive");
        Self {
            min: b.min.to_array(),
            offset: first,
            max: b.max.to_array(),
            count,
        }
    }

    #[inline]
    pub fn interior(b: Aabb, second_child: u32) -> Self {
        Self {
            min: b.min.to_array(),
            offset: second_child,
            max: b.max.to_array(),
            count: 0,
        }
    }

    #[inline(always)]
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }

    #[inline]
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: Vec3A::from_array(self.min),
            max: Vec3A::from_array(self.max),
        }
    }

    /// Entry distance or `INFINITY`. Node boxes are never empty (the build
    /// drops primitives with empty bounds) and are already padded, so the
    /// bare slab test is exact enough.
    #[inline(always)]
    pub fn hit(&self, o: Vec3A, inv_d: Vec3A, t_max: f32) -> f32 {
        slab(
            Vec3A::from_array(self.min),
            Vec3A::from_array(self.max),
            o,
            inv_d,
            t_max,
        )
    }
}
