//! The runtime scene: what rays query — shapes and their BVHs, materials,
//! textures and lights — with glam types and u32 indices; no names, no
//! options, no serde. Camera, film and integrator are the [`crate::view::View`]
//! beside it (pbrt keeps the aggregate apart from camera and film too). Built
//! once by [`crate::load`], never mutated while rendering.

use crate::accel::WideBvh;
use crate::geometry::MeshHit;
use crate::geometry::shape_lanes::{LaneHit, ShapeLanes};
use crate::geometry::triangle::WatertightRay4;
use crate::geometry::{Geometry, Hit, Shape};
use crate::lights::{CausticEmitters, EnvironmentLight, Light, LightPicker};
use crate::materials::surface::{self, Surface};
use crate::materials::{Material, Texture};
use crate::math::float_error::offset_along_normal;
use crate::math::{Frame, Ray};
use crate::media::Media;
use glam::{Vec2, Vec3A};

/// The runtime scene: everything rays query, in world space, indexed by `u32`.
pub struct Scene {
    /// Runtime materials, indexed by [`Hit::material`].
    pub materials: Vec<Material>,
    /// What each material does to the surface (normal maps, cut-outs),
    /// indexed like `materials`; shorter (often empty) when the rest do
    /// nothing.
    pub surfaces: Vec<Surface>,
    /// A black material: what a hit shades with when its perturbed normal
    /// faces away from the ray (`materials::surface`).
    pub black: u32,
    /// Decoded image textures, indexed by [`crate::materials::ImageLookup::index`].
    pub textures: Vec<Texture>,
    /// Light sources, indexed by [`Hit::light`]; area lights and emissive
    /// shapes are also surfaces in `shapes`.
    pub lights: Vec<Light>,
    /// Index in `lights` of the environment, if the scene has one: what rays
    /// that miss everything see.
    pub environment: Option<u32>,
    /// Chooses the light for next-event estimation.
    pub light_picker: LightPicker,
    /// Bounded shapes first (`..bounded`, in the BVH's leaf order), then
    /// unbounded ones (planes), which every ray tests.
    pub shapes: Vec<Shape>,
    /// The object each of `shapes` belongs to, for the object-index layer:
    /// 1 + its index in the scene file's `objects`, then the area lights
    /// (`1 + objects.len() + i` for `lights[i]`).
    pub objects: Vec<u32>,
    /// Number of bounded shapes at the front of `shapes` (those in the BVH).
    pub bounded: u32,
    /// Meshes (each with its own BVH) and their instances.
    pub geometry: Geometry,
    /// The top-level BVH over the bounded shapes.
    pub bvh: WideBvh,
    /// The bounded shapes in SIMD lanes when they are a few spheres and
    /// quads (see [`ShapeLanes`]): tested all at once, not through `bvh`.
    pub lanes: Option<ShapeLanes>,
    /// For each of `shapes`, whether a material it is drawn with has a
    /// cut-out (a shadow ray may pass through it); empty when no material
    /// has one.
    pub cut: Vec<bool>,
    /// The lights caustic connections emit from, when the scene has
    /// perfect-specular surfaces for them to matter.
    pub caustics: Option<CausticEmitters>,
    /// Each material's absorption coefficient inside the solid it bounds
    /// (`Material::interior`: `None` for surfaces light does not enter),
    /// indexed like `materials`; empty when no material absorbs, so clear
    /// scenes skip the bookkeeping.
    pub absorption: Vec<Option<crate::math::Rgb>>,
    /// Participating media, when the scene declares any: the path tracer
    /// takes its volumetric branch only then (`integrators::vol_path`).
    pub media: Option<Box<Media>>,
}

/// What the nearest hit so far needs for its hit record beyond `t`.
#[derive(Clone, Copy)]
enum Nearest {
    Shape(u32),
    /// Shape index, instance index, hit.
    Mesh(u32, u32, MeshHit),
    Triangle(u32, Vec2),
    /// Shape index of a triangle pair, which of the two, barycentrics.
    MeshQuad(u32, u32, Vec2),
    /// Shape index of a quad and the hit's `(s, t)`.
    Quad(u32, Vec2),
}

/// A [`Nearest`] as three 64-bit words, the form the traversal's leaf test
/// stores it in. `Path::trace` reads the nearest hit back a moment after
/// the traversal wrote it; as the enum, the writer stored its fields one
/// by one (4 bytes each) and the reader copied it by 8-byte words across
/// two of those stores, which store forwarding cannot serve (8% of
/// `Path::trace`'s samples on the Cornell box, perf). Words written whole
/// are read back whole.
#[derive(Clone, Copy)]
struct NearestWords([u64; 3]);

impl NearestWords {
    /// No hit.
    const NONE: Self = Self([0; 3]);
}

/// Two floats as one word, `x` in the low half.
#[inline(always)]
fn pack(v: Vec2) -> u64 {
    u64::from(v.x.to_bits()) | (u64::from(v.y.to_bits()) << 32)
}

#[inline(always)]
fn unpack(w: u64) -> Vec2 {
    Vec2::new(f32::from_bits(w as u32), f32::from_bits((w >> 32) as u32))
}

impl Nearest {
    /// The index in `shapes` of the shape hit.
    #[inline(always)]
    fn shape(self) -> u32 {
        match self {
            Nearest::Shape(i)
            | Nearest::Mesh(i, ..)
            | Nearest::Triangle(i, _)
            | Nearest::MeshQuad(i, ..)
            | Nearest::Quad(i, _) => i,
        }
    }

    /// Word 0: the variant (1 to 5) and the shape index; word 1: the
    /// instance or the half of a pair, and a mesh triangle; word 2: the
    /// two floats.
    #[inline(always)]
    fn encode(self) -> NearestWords {
        let head = |kind: u64, i: u32| kind | (u64::from(i) << 32);
        let pair = |a: u32, b: u32| u64::from(a) | (u64::from(b) << 32);
        NearestWords(match self {
            Nearest::Shape(i) => [head(1, i), 0, 0],
            Nearest::Mesh(i, k, h) => [head(2, i), pair(k, h.tri), pack(h.bc)],
            Nearest::Triangle(i, bc) => [head(3, i), 0, pack(bc)],
            Nearest::MeshQuad(i, k, bc) => [head(4, i), pair(k, 0), pack(bc)],
            Nearest::Quad(i, uv) => [head(5, i), 0, pack(uv)],
        })
    }

    /// The hit `w` holds, at distance `t` (a mesh hit's own `t`), or `None`.
    #[inline(always)]
    fn decode(w: NearestWords, t: f32) -> Option<Self> {
        let [head, pair, floats] = w.0;
        let i = (head >> 32) as u32;
        let (a, b) = (pair as u32, (pair >> 32) as u32);
        Some(match head as u32 {
            1 => Nearest::Shape(i),
            2 => Nearest::Mesh(
                i,
                a,
                MeshHit {
                    t,
                    tri: b,
                    bc: unpack(floats),
                },
            ),
            3 => Nearest::Triangle(i, unpack(floats)),
            4 => Nearest::MeshQuad(i, a, unpack(floats)),
            5 => Nearest::Quad(i, unpack(floats)),
            _ => return None,
        })
    }
}

impl Scene {
    /// The environment and its index in `lights`, if the scene has one.
    #[inline]
    pub fn environment(&self) -> Option<(u32, &EnvironmentLight)> {
        let i = self.environment?;
        self.lights[i as usize].as_environment().map(|e| (i, e))
    }

    /// Closest hit in `(0, t_max)`. Inlined into the integrators: returned
    /// from a call, the caller copied the hit record out of the callee's
    /// stores with wider loads, which cannot be forwarded from them (a stall
    /// perf put at 10% of `Path::trace`'s samples); inlined, the fields
    /// stay where they are made. 1–2.5% faster on the Cornell boxes and the
    /// sphere scenes (256², alternated runs).
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.closest(ray, t_max).map(|(hit, _)| hit)
    }

    /// [`Scene::intersect`] into `out`: whether there is a hit, its record
    /// written field by field where the caller keeps it. Returned as an
    /// `Option`, the record was moved by wider loads than the stores that
    /// made it, which store forwarding cannot serve (8% of
    /// `Path::trace`'s samples on the Cornell box, perf).
    #[inline(always)]
    pub fn intersect_into(&self, ray: &Ray, t_max: f32, out: &mut Hit) -> bool {
        let found = if self.surfaces.is_empty() {
            // The record made right here, not in a closure passed to
            // `Option::map`: LLVM kept that closure out of line, a call with
            // six saved registers per hit (2.5% of the OBJ room's
            // instructions, 3% of `cornell.ron`'s; callgrind). An early
            // return here instead of `found` cost 0.7% of that back.
            let found = self.nearest(ray, t_max);
            if let Some((nearest, t)) = found {
                self.resolve_into(ray, nearest, t, out);
            }
            found.map(|_| ())
        } else {
            self.nearest(ray, t_max)
                .and_then(|(nearest, t)| self.apply_surface(ray, t_max, nearest, t, true, out))
                .map(|_| ())
        };
        found.is_some()
    }

    /// Closest hit in `(0, t_max)` and the object id ([`Scene::objects`])
    /// of the shape hit: the object-index layer's query.
    pub fn intersect_object(&self, ray: &Ray, t_max: f32) -> Option<(Hit, u32)> {
        self.closest(ray, t_max)
            .map(|(hit, shape)| (hit, self.objects.get(shape as usize).copied().unwrap_or(0)))
    }

    /// [`Scene::intersect_object`] with the hit record written into `out`
    /// (see [`Scene::intersect_into`]): the object id, or `None` (and `out`
    /// unspecified) when nothing is hit.
    #[inline(always)]
    pub fn intersect_object_into(&self, ray: &Ray, t_max: f32, out: &mut Hit) -> Option<u32> {
        let (nearest, t) = self.nearest(ray, t_max)?;
        let shape = if self.surfaces.is_empty() {
            self.resolve_into(ray, nearest, t, out);
            nearest.shape()
        } else {
            self.apply_surface(ray, t_max, nearest, t, true, out)?
        };
        Some(self.objects.get(shape as usize).copied().unwrap_or(0))
    }

    /// Closest hit in `(0, t_max)` and the index in `shapes` of the shape
    /// hit. Inlined into both callers, so `intersect` pays nothing for the
    /// index it drops.
    #[inline(always)]
    fn closest(&self, ray: &Ray, t_max: f32) -> Option<(Hit, u32)> {
        // Straight from the traversal when no material changes the
        // surface: going through a second `Option` moved each hit record
        // once more (2% of the Cornell box's instructions).
        if self.surfaces.is_empty() {
            self.closest_surface(ray, t_max)
        } else {
            self.closest_with_surfaces(ray, t_max)
        }
    }

    /// [`Scene::closest`] in a scene with normal maps or cut-outs.
    #[inline(never)]
    fn closest_with_surfaces(&self, ray: &Ray, t_max: f32) -> Option<(Hit, u32)> {
        let (nearest, t) = self.nearest(ray, t_max)?;
        let mut hit = Hit::default();
        let shape = self.apply_surface(ray, t_max, nearest, t, true, &mut hit)?;
        Some((hit, shape))
    }

    /// The material's effect on the surface at `hit` (shape index `shape`)
    /// on `ray`: past a cut-out the ray goes on (up to 64 of them), and,
    /// when `shading`, a normal or bump map replaces the shading normal — or
    /// makes the hit black when the new normal faces away from the ray
    /// (`materials::surface`). Shadow rays pass `false`: whether a surface
    /// blocks does not depend on its shading normal, and the map lookup and
    /// tangent frame were a third of a shadow ray's cost on a normal-mapped
    /// floor. The cut-out decisions are the same either way.
    #[inline(never)]
    fn apply_surface(
        &self,
        ray: &Ray,
        t_max: f32,
        mut nearest: Nearest,
        t: f32,
        shading: bool,
        hit: &mut Hit,
    ) -> Option<u32> {
        let mut shape;
        (*hit, shape) = self.resolve(ray, nearest, t);
        let (mut r, mut traveled) = (*ray, 0.0);
        let mut blend_u: Option<f32> = None;
        let mut colored = false;
        for _ in 0..64 {
            let Some(s) = self.surfaces.get(hit.material as usize) else {
                break;
            };
            if s.vertex_color && !colored {
                hit.color = self.vertex_color(nearest);
                colored = true;
            }
            if let Some(b) = &s.blend {
                // One of the two shades this hit; its own cut-out, normal
                // map or blend comes next (the same ray, the same hit).
                let u = blend_u.get_or_insert_with(|| surface_number(&r, hit.t, shape, BLEND_SALT));
                (hit.material, *u) = b.pick(&crate::materials::TexPoint::at(hit), &self.textures, *u);
                continue;
            }
            if let Some(c) = &s.cutout
                && !c.present(
                    &crate::materials::TexPoint::at(hit),
                    &self.textures,
                    surface_number(&r, hit.t, shape, CUTOUT_SALT),
                )
            {
                // Go on from just beyond the surface, along the same line.
                traveled += hit.t;
                r = Ray::new(offset_along_normal(hit.p, hit.ng, hit.p_error, r.d), r.d);
                let t;
                (nearest, t) = self.nearest(&r, t_max - traveled)?;
                (*hit, shape) = self.resolve(&r, nearest, t);
                blend_u = None;
                colored = false;
                continue;
            }
            if shading && let Some(p) = &s.normal {
                let (dpdu, dpdv, sign) = self.derivatives(hit, shape, nearest, p);
                let ns = p.normal(
                    hit.ns,
                    dpdu,
                    dpdv,
                    sign,
                    &crate::materials::TexPoint::at(hit),
                    &self.textures,
                );
                if !surface::valid_for(ray.d, hit.ns, ns) {
                    hit.material = self.black;
                }
                hit.ns = ns;
            }
            break;
        }
        hit.t += traveled;
        Some(shape)
    }

    /// ∂p/∂u, ∂p/∂v and the tangent's handedness at the shape hit:
    /// analytic on quads and spheres; on meshes the tangent `p` asks for
    /// (the vertex tangents or the triangle's ∂p/∂u, carried to world space
    /// by the instance); elsewhere an arbitrary tangent frame.
    fn derivatives(
        &self,
        hit: &Hit,
        shape: u32,
        nearest: Nearest,
        p: &surface::Perturb,
    ) -> (Vec3A, Vec3A, f32) {
        let frame = match p {
            surface::Perturb::NormalMap { frame, .. } => *frame,
            surface::Perturb::Bump { .. } => crate::geometry::TangentFrame::Vertex,
        };
        let tangent = self.mesh_triangle(nearest).and_then(|(k, h)| {
            self.geometry
                .instances
                .get(k as usize)?
                .tangent(h, frame, &self.geometry.meshes)
        });
        if let Some(t) = tangent {
            let s = Vec3A::from(t.truncate());
            return (s, t.w * hit.ns.cross(s), t.w);
        }
        match self.shapes.get(shape as usize) {
            Some(Shape::Quad(q)) => (q.u, q.v, 1.0),
            Some(Shape::Sphere(s)) => {
                let (u, v) = s.derivatives(hit.ng);
                (u, v, 1.0)
            }
            _ => {
                let f = Frame::from_normal(hit.ns);
                (f.s, f.t, 1.0)
            }
        }
    }

    /// Closest hit of any surface, cut-out or not.
    #[inline(always)]
    fn closest_surface(&self, ray: &Ray, t_max: f32) -> Option<(Hit, u32)> {
        let (nearest, t) = self.nearest(ray, t_max)?;
        Some(self.resolve(ray, nearest, t))
    }

    /// The nearest surface along `ray` and its `t`, before its hit record.
    #[inline(always)]
    fn nearest(&self, ray: &Ray, t_max: f32) -> Option<(Nearest, f32)> {
        let geo = &self.geometry;
        let shapes = &self.shapes;
        // Kept with the nearest hit so the hit record needs no second trace
        // (the BVH only asks for hits below the current best).
        let mut nearest = NearestWords::NONE;
        // The watertight triangle setup (an axis choice and three divisions)
        // is made on the first triangle the ray meets: many rays meet none.
        let mut wt = None;
        let best = if let Some(lanes) = &self.lanes {
            lanes.closest(ray, t_max).map(|(t, h)| {
                nearest = match h {
                    LaneHit::Sphere(i) => Nearest::Shape(i),
                    LaneHit::Quad(i, uv) => Nearest::Quad(i, uv),
                }
                .encode();
                t
            })
        } else {
            self.bvh.intersect(ray, t_max, |first, count, mut t_best| {
                let mut found = None;
                for i in first..first + count {
                    let (t, n) = match &shapes[i as usize] {
                        Shape::Instance(k) => {
                            let Some(h) = geo.instances[*k as usize].closest(ray, t_best, &geo.meshes) else {
                                continue;
                            };
                            (h.t, Nearest::Mesh(i, *k, h))
                        }
                        Shape::Triangle(tr) => {
                            let wt = WatertightRay4::lazily(&mut wt, ray);
                            let Some((t, bc)) = tr.intersect(wt, t_best) else {
                                continue;
                            };
                            (t, Nearest::Triangle(i, bc))
                        }
                        Shape::MeshQuad(q) => {
                            let wt = WatertightRay4::lazily(&mut wt, ray);
                            let Some((t, k, bc)) = q.intersect(wt, t_best) else {
                                continue;
                            };
                            (t, Nearest::MeshQuad(i, k, bc))
                        }
                        // The common analytic shapes inline (the shared match
                        // in `intersect_t` stayed an out-of-line call).
                        Shape::Quad(q) => {
                            let Some((t, uv)) = q.intersect(ray, t_best) else {
                                continue;
                            };
                            (t, Nearest::Quad(i, uv))
                        }
                        Shape::Sphere(sp) => {
                            let Some(t) = sp.intersect(ray, t_best) else {
                                continue;
                            };
                            (t, Nearest::Shape(i))
                        }
                        s => {
                            let Some(t) = s.intersect_t(ray, t_best, geo) else {
                                continue;
                            };
                            (t, Nearest::Shape(i))
                        }
                    };
                    t_best = t;
                    found = Some(t);
                    nearest = n.encode();
                }
                found
            })
        };
        let mut t_best = best.unwrap_or(t_max);
        for i in self.bounded..self.shapes.len() as u32 {
            if let Some(t) = shapes[i as usize].intersect_t(ray, t_best, geo) {
                t_best = t;
                nearest = Nearest::Shape(i).encode();
            }
        }
        Some((Nearest::decode(nearest, t_best)?, t_best))
    }

    /// [`Scene::resolve`]'s record written into `out`, each arm but the
    /// rarer analytic shapes storing straight there (see
    /// [`Scene::intersect_into`]). Kept beside `resolve` rather than under
    /// it: `resolve` written through this function made the Cornell box 7%
    /// slower (the compiler laid the shared arms out differently).
    #[inline(always)]
    fn resolve_into(&self, ray: &Ray, nearest: Nearest, t_best: f32, out: &mut Hit) {
        let geo = &self.geometry;
        let shapes = &self.shapes;
        match nearest {
            Nearest::Mesh(_, k, h) => *out = geo.instances[k as usize].hit(ray, h, &geo.meshes),
            Nearest::Triangle(i, bc) => match &shapes[i as usize] {
                Shape::Triangle(tr) => tr.hit_into(ray, t_best, bc, geo, out),
                s => *out = s.hit(ray, t_best, geo),
            },
            Nearest::MeshQuad(i, k, bc) => match &shapes[i as usize] {
                Shape::MeshQuad(q) => q.hit_into(ray, t_best, k, bc, geo, out),
                s => *out = s.hit(ray, t_best, geo),
            },
            Nearest::Quad(i, uv) => match &shapes[i as usize] {
                Shape::Quad(q) => *out = q.hit_at(ray, t_best, uv),
                s => *out = s.hit(ray, t_best, geo),
            },
            Nearest::Shape(_) => *out = self.resolve(ray, nearest, t_best).0,
        }
    }

    /// The hit record of the nearest surface found by [`Scene::nearest`].
    #[inline(always)]
    fn resolve(&self, ray: &Ray, nearest: Nearest, t_best: f32) -> (Hit, u32) {
        let geo = &self.geometry;
        let shapes = &self.shapes;
        match nearest {
            Nearest::Mesh(i, k, h) => (geo.instances[k as usize].hit(ray, h, &geo.meshes), i),
            Nearest::Triangle(i, bc) => match &shapes[i as usize] {
                Shape::Triangle(tr) => (tr.hit(ray, t_best, bc, geo), i),
                s => (s.hit(ray, t_best, geo), i),
            },
            Nearest::MeshQuad(i, k, bc) => match &shapes[i as usize] {
                Shape::MeshQuad(q) => (q.hit(ray, t_best, k, bc, geo), i),
                s => (s.hit(ray, t_best, geo), i),
            },
            Nearest::Quad(i, uv) => match &shapes[i as usize] {
                Shape::Quad(q) => (q.hit_at(ray, t_best, uv), i),
                s => (s.hit(ray, t_best, geo), i),
            },
            Nearest::Shape(i) => match &shapes[i as usize] {
                Shape::Sphere(sp)
                    if !self.materials[sp.material as usize].is_textured()
                        && self
                            .surfaces
                            .get(sp.material as usize)
                            .is_none_or(Surface::is_plain) =>
                {
                    (sp.hit_without_uv(ray.at(t_best), t_best), i)
                }
                s => (s.hit(ray, t_best, geo), i),
            },
        }
    }

    /// The mesh triangle behind a nearest hit (instance and the mesh's own
    /// triangle and barycentrics), for tangent frames; `None` off meshes.
    fn mesh_triangle(&self, nearest: Nearest) -> Option<(u32, MeshHit)> {
        match nearest {
            Nearest::Mesh(_, k, h) => Some((k, h)),
            Nearest::Triangle(i, bc) => match self.shapes.get(i as usize)? {
                Shape::Triangle(tr) => Some((
                    tr.instance,
                    MeshHit {
                        t: 0.0,
                        tri: tr.tri,
                        bc,
                    },
                )),
                _ => None,
            },
            Nearest::MeshQuad(i, k, bc) => match self.shapes.get(i as usize)? {
                Shape::MeshQuad(q) => Some((q.instance, q.mesh_hit(0.0, k, bc))),
                _ => None,
            },
            Nearest::Shape(_) | Nearest::Quad(..) => None,
        }
    }

    /// The vertex colour at a mesh hit, white elsewhere and on meshes
    /// without colours.
    fn vertex_color(&self, nearest: Nearest) -> crate::math::Rgb {
        self.mesh_triangle(nearest)
            .and_then(|(k, h)| {
                let instance = self.geometry.instances.get(k as usize)?;
                self.geometry
                    .meshes
                    .get(instance.mesh as usize)?
                    .color(h.tri, h.bc)
            })
            .unwrap_or(crate::math::Rgb::ONE)
    }

    /// Whether anything blocks `ray` before `t_max` (shadow rays). Cut-outs
    /// let it through where they are transparent.
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        if !self.cut.is_empty() {
            // The nearest surface decides, past the cut-outs' holes. A shape
            // without a cut-out blocks: no hit record is needed to say so.
            let Some((nearest, t)) = self.nearest(ray, t_max) else {
                return false;
            };
            if !self.cut.get(nearest.shape() as usize).copied().unwrap_or(true) {
                return true;
            }
            return self
                .apply_surface(ray, t_max, nearest, t, false, &mut Hit::default())
                .is_some();
        }
        let geo = &self.geometry;
        let shapes = &self.shapes;
        if (self.bounded..self.shapes.len() as u32).any(|i| shapes[i as usize].occludes(ray, t_max, geo)) {
            return true;
        }
        if let Some(lanes) = &self.lanes {
            return lanes.occluded(ray, t_max);
        }
        let mut wt = None;
        self.bvh.occluded(ray, t_max, |first, count, t_max| {
            shapes[first as usize..(first + count) as usize]
                .iter()
                .any(|s| match s {
                    Shape::Triangle(tr) => tr
                        .intersect(WatertightRay4::lazily(&mut wt, ray), t_max)
                        .is_some(),
                    Shape::MeshQuad(q) => q.intersect(WatertightRay4::lazily(&mut wt, ray), t_max).is_some(),
                    Shape::Quad(q) => q.intersect(ray, t_max).is_some(),
                    Shape::Sphere(sp) => sp.intersect(ray, t_max).is_some(),
                    s => s.occludes(ray, t_max, geo),
                })
        })
    }
}

/// [`surface_number`]'s salt for a stochastic cut-out.
const CUTOUT_SALT: u32 = 0;
/// [`surface_number`]'s salt for a blend's choice (independent of the
/// cut-out's number at the same hit).
const BLEND_SALT: u32 = 0x6a09_e667;

/// The uniform number in [0, 1) a stochastic cut-out compares its opacity
/// with, or a blend its weight: a hash of the ray and the hit, so it is the
/// same for the same ray whatever thread traces it, and independent between
/// rays, surfaces and salts.
fn surface_number(r: &Ray, t: f32, shape: u32, salt: u32) -> f32 {
    let mut h: u32 = (shape ^ salt).wrapping_mul(0x9e37_79b9);
    for x in [r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, t] {
        h = (h ^ x.to_bits()).wrapping_mul(0x85eb_ca6b);
        h ^= h >> 15;
    }
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^= h >> 16;
    (h >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every variant comes back from its words as it went in, bit for bit
    /// (a mesh hit's `t` is the distance the words are read with), and the
    /// empty words are no hit.
    #[test]
    fn nearest_words_hold_every_variant() {
        let v = Vec2::new(0.25, -0.0);
        let odd = Vec2::new(f32::from_bits(1), 1.0 - f32::EPSILON);
        let t = 3.5;
        let cases = [
            Nearest::Shape(7),
            Nearest::Shape(u32::MAX),
            Nearest::Mesh(
                1,
                u32::MAX,
                MeshHit {
                    t,
                    tri: 123_456,
                    bc: odd,
                },
            ),
            Nearest::Triangle(0, v),
            Nearest::MeshQuad(9, 1, odd),
            Nearest::Quad(u32::MAX - 1, v),
        ];
        let bits = |v: Vec2| v.to_array().map(f32::to_bits);
        for n in cases {
            let back = Nearest::decode(n.encode(), t).expect("a hit");
            let same = match (n, back) {
                (Nearest::Shape(a), Nearest::Shape(b)) => a == b,
                (Nearest::Mesh(a, k, h), Nearest::Mesh(b, l, g)) => {
                    (a, k, h.tri, h.t.to_bits(), bits(h.bc)) == (b, l, g.tri, g.t.to_bits(), bits(g.bc))
                }
                (Nearest::Triangle(a, x), Nearest::Triangle(b, y))
                | (Nearest::Quad(a, x), Nearest::Quad(b, y)) => a == b && bits(x) == bits(y),
                (Nearest::MeshQuad(a, k, x), Nearest::MeshQuad(b, l, y)) => {
                    (a, k, bits(x)) == (b, l, bits(y))
                }
                _ => false,
            };
            assert!(same, "variant {} changed on the way", n.shape());
            assert_eq!(back.shape(), n.shape());
        }
        assert!(Nearest::decode(NearestWords::NONE, t).is_none());
    }
}
