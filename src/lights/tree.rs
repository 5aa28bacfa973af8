//! A light tree: next-event estimation picks the light to sample in
//! proportion to an estimate of what it sends to the shading point, not its
//! power alone (pbrt-v4's `BVHLightSampler`, after Conty Estevez & Kulla
//! 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting",
//! <https://doi.org/10.1145/3233305>).
//!
//! Why: with power alone, a shading point near one of a hundred lamps sends
//! 99% of its shadow rays to lamps too far or facing away to matter. Each
//! node of the tree bounds its lights' positions (a box), emitting normals
//! (a cone around `w` of half-angle θo) and emission spread beyond the
//! normal (θe: π/2 for a surface); from a point `p` with normal `n` its
//! *importance* is `Φ · cos θ' / d²`, where `d` is the distance to the box
//! centre (at least half the box's diagonal) and θ' the smallest angle,
//! over the box, between the emission cone and the direction to `p`
//! (zero beyond θo + θe: a one-sided light facing away gets nothing),
//! times the largest `|cos|` the box can make with `n`. Sampling walks
//! down from the root choosing each child in proportion to its importance;
//! the probability of a light is the product along its path, which
//! [`LightTree::pmf`] recomputes from the light's bit trail for MIS.
//!
//! The importance is zero only where no light of the node can reach `p`
//! (behind every one-sided emitter, outside every spot cone), so no light
//! that contributes is ever given probability zero: the estimate stays
//! unbiased whatever the tree's shape. Each node has four children, their
//! importances computed in one SIMD pass: a pick is a chain of dependent
//! square roots and divisions per level, so half the levels of pbrt's
//! binary tree is half the wait (on `scenes/many_lights.ron`, 64 lamps, the
//! binary tree cost 1.7–1.9× the power picker per sample). Children come
//! from two median splits of the node's lights, each along the longest axis
//! of the centroids (pbrt uses a surface-area-orientation cost; this one is
//! simpler, and `log4` of the light count deep).
//!
//! Directional lights (suns) are not in the tree either: each is weighed
//! beside it by π × the irradiance it gives the point's surface, `π E
//! |cos θ|` (π E for a point with no surface), the same units as a point
//! lamp's `π I / d²`.
//!
//! The environment is not in the tree (it has no position): at each point
//! it is weighed against the tree's root by its own importance in the same
//! units, π × its unoccluded irradiance on the point's surface, times the
//! share of that irradiance BSDF sampling would not find by itself (none of
//! a constant sky, nearly all of a sun: `irradiance.rs`, [`SkyWeight`]),
//! times the share of the sky the camera's surfaces were measured to see
//! (`integrators/sky_visibility.rs`). Its power through the scene's
//! bounding disk, as pbrt-v4 weighs it, grows with the scene's size: a
//! 40 × 40 floor under a dim sky sent ~90% of the shadow rays to the sky
//! while one area light did nearly all the lighting, and the image was up
//! to 2.2× noisier than Mitsuba 3's (issue 37). The lights' weights are in
//! the same units (what each sends one point, not its power:
//! [`light_bounds`]).
//!
//! Every estimate here ignores occlusion and can be wrong (a sky over a
//! closed room, a lamp behind a wall), so the pick is a defensive mixture:
//! with probability [`UNIFORM_SHARE`] a light is chosen uniformly among
//! all lights with power, else by the estimate. Every light then keeps at
//! least `UNIFORM_SHARE / N` wherever it is, and no scene can do much worse
//! than uniform selection (at most `1 / UNIFORM_SHARE` times its variance,
//! where the estimate is wholly wrong); where the estimate is right the
//! mixture costs little (see `docs/benchmarks.md`, open scenes).

use super::Light;
use super::irradiance::SkyWeight;
use crate::accel::Aabb;
use crate::math::luminance;
use glam::{BVec4A, Quat, Vec3A, Vec4};
use std::f32::consts::PI;

/// What bounds a light or a group of lights (pbrt-v4's `LightBounds`).
#[derive(Clone, Copy, Debug)]
pub struct LightBounds {
    /// Where the emitting points are.
    pub bounds: Aabb,
    /// Axis of the cone holding every emitting normal.
    pub w: Vec3A,
    /// The light's weight in the tree: π × the largest radiant intensity
    /// (luminance, W/sr) it sends one way, so that `phi · cos θ' / d²` is π
    /// × the irradiance it can give a point facing it, in the units of the
    /// sky's weight (see [`light_bounds`]). Sums over a node's lights.
    pub phi: f32,
    /// Cosine of the normal cone's half-angle θo (−1: any direction).
    pub cos_theta_o: f32,
    /// Cosine of how far beyond its normal a point emits, θe (0 for a
    /// surface: a hemisphere).
    pub cos_theta_e: f32,
    /// Whether the back of each emitter emits too.
    pub two_sided: bool,
}

#[inline]
fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

impl LightBounds {
    /// Bounds of both (pbrt-v4's `Union`).
    pub fn union(&self, o: &LightBounds) -> LightBounds {
        if self.phi == 0.0 {
            return *o;
        }
        if o.phi == 0.0 {
            return *self;
        }
        let (w, cos_theta_o) = cone_union((self.w, self.cos_theta_o), (o.w, o.cos_theta_o));
        LightBounds {
            bounds: self.bounds.union(o.bounds),
            w,
            phi: self.phi + o.phi,
            cos_theta_o,
            cos_theta_e: self.cos_theta_e.min(o.cos_theta_e),
            two_sided: self.two_sided || o.two_sided,
        }
    }
}

/// The smallest cone (axis, cos half-angle) holding two cones (pbrt-v4's
/// `Union(DirectionCone, DirectionCone)`).
fn cone_union(a: (Vec3A, f32), b: (Vec3A, f32)) -> (Vec3A, f32) {
    const SPHERE: (Vec3A, f32) = (Vec3A::Z, -1.0);
    let theta_a = a.1.clamp(-1.0, 1.0).acos();
    let theta_b = b.1.clamp(-1.0, 1.0).acos();
    let theta_d = a.0.dot(b.0).clamp(-1.0, 1.0).acos();
    if (theta_d + theta_b).min(PI) <= theta_a {
        return a;
    }
    if (theta_d + theta_a).min(PI) <= theta_b {
        return b;
    }
    let theta_o = 0.5 * (theta_a + theta_d + theta_b);
    if theta_o >= PI {
        return SPHERE;
    }
    let axis = a.0.cross(b.0);
    if axis.length_squared() < 1e-12 {
        return SPHERE;
    }
    let w = Quat::from_axis_angle(axis.normalize().into(), theta_o - theta_a) * glam::Vec3::from(a.0);
    // Rounding in the rotation could leave an edge direction a hair
    // outside: widen by a little (a wider cone is still a bound).
    (
        Vec3A::from(w).normalize(),
        (theta_o * 1.0001 + 1e-5).min(PI).cos(),
    )
}

/// Bounds of one light; `None` for the environment (infinitely far). Each
/// light says what bounds it ([`Light::bounds`], beside its model), given
/// its power `Φ` (luminance), and turns it into its weight: what it sends
/// toward one point, not in all directions. A one-sided flat emitter of
/// area `A` sends its most, `L·A` W/sr, along its normal, and `Φ = π·L·A`:
/// its weight is its power. A sphere's is a quarter of its power (`π·L·πr²`
/// against `Φ = π·L·4πr²`: only the disk it shows a point sends), a
/// point's too (`π·I` against `4π·I`), a two-sided surface's half. The sky
/// is weighed by π × its irradiance at the point (at most), so the tree's
/// weights must be in the same units: with powers, a sphere or a point
/// lamp beside a sunny sky took four times its share of the shadow rays,
/// and on an open ground lit by a sun and two small lamps the direct light
/// was seven times as noisy as each part rendered alone (issue 37).
pub fn light_bounds(light: &Light) -> Option<LightBounds> {
    let phi = luminance(light.power()).max(0.0);
    let phi = if phi.is_finite() { phi } else { 0.0 };
    light.bounds(phi)
}

/// The largest share of its area a surface whose normals fill a cone of
/// half-angle θo (`cos_theta_o`) shows one direction, taking it to be a
/// spherical cap: `(1 + cos θo) / 2` up to a hemisphere (1 for a flat
/// emitter, ½ for a half sphere), then its outline's disk over its area,
/// `1 / (2 (1 − cos θo))`, down to ¼ for a whole sphere (a convex closed
/// surface shows a quarter of its area on average, Cauchy's formula).
pub fn projected_share(cos_theta_o: f32) -> f32 {
    let c = cos_theta_o.clamp(-1.0, 1.0);
    if c >= 0.0 {
        0.5 * (1.0 + c)
    } else {
        0.5 / (1.0 - c)
    }
}

impl LightBounds {
    /// An emitting surface of power `phi`: its points in `bounds`, its
    /// normals in the cone (`w`, `cos_theta_o`), each emitting over its
    /// hemisphere (θe = π/2). Its weight is its power times the share of
    /// its area it can show one point ([`projected_share`]), halved when
    /// two-sided (the power counts both sides; a point sees one).
    pub fn surface(bounds: Aabb, w: Vec3A, cos_theta_o: f32, two_sided: bool, phi: f32) -> Self {
        let sides = if two_sided { 0.5 } else { 1.0 };
        LightBounds {
            bounds,
            w,
            phi: phi * sides * projected_share(cos_theta_o),
            cos_theta_o,
            cos_theta_e: 0.0,
            two_sided,
        }
    }

    /// The box around the ball of centre `c` and radius `r` (a point when
    /// `r` is 0).
    pub fn ball(c: Vec3A, r: f32) -> Aabb {
        Aabb {
            min: c - Vec3A::splat(r),
            max: c + Vec3A::splat(r),
        }
    }
}

/// Children per node: four, in SIMD lanes, so a pick walks half the levels
/// of a binary tree and weighs all children of a level in one pass.
const WIDTH: usize = 4;

/// The first step of a pick at a shading point: the weight of the lights
/// beside the tree (the sky and any directional lights, summed) and the
/// root's child weights and their total ([`LightTree::top`]). A path keeps
/// the one of its last vertex: the density of the light its next BSDF
/// sample reaches is judged from that vertex again ([`LightTree::pmf_from`]),
/// and recomputing it there was half of `top`'s cost (9% of
/// `textured_spheres`' time, perf).
pub type Top = (f32, Option<([f32; WIDTH], f32)>);
/// A child reference: a node index, or (top bit set) a light index.
const LEAF: u32 = 1 << 31;
/// An unused child slot; its lanes hold no power, so its importance is 0.
const EMPTY: u32 = u32::MAX;

/// Four children's bounds, lane `k` for child `k`, in the form their
/// importance reads: box centre, squared radius of the box's bounding
/// sphere, the distance² floor (half the diagonal, as pbrt), the normal
/// cone's axis, cosine and sine.
#[derive(Clone, Copy, Debug)]
struct Node {
    pc: [Vec4; 3],
    w: [Vec4; 3],
    radius2: Vec4,
    d2_floor: Vec4,
    phi: Vec4,
    cos_o: Vec4,
    sin_o: Vec4,
    cos_e: Vec4,
    two_sided: BVec4A,
    child: [u32; WIDTH],
}

/// `cos(max(0, a − b))` per lane.
#[inline(always)]
fn cos_sub_clamped4(sin_a: Vec4, cos_a: Vec4, sin_b: Vec4, cos_b: Vec4) -> Vec4 {
    Vec4::select(cos_a.cmpgt(cos_b), Vec4::ONE, cos_a * cos_b + sin_a * sin_b)
}

/// `sin(max(0, a − b))` per lane.
#[inline(always)]
fn sin_sub_clamped4(sin_a: Vec4, cos_a: Vec4, sin_b: Vec4, cos_b: Vec4) -> Vec4 {
    Vec4::select(cos_a.cmpgt(cos_b), Vec4::ZERO, sin_a * cos_b - cos_a * sin_b)
}

#[inline(always)]
fn sqrt0(x: Vec4) -> Vec4 {
    x.max(Vec4::ZERO).sqrt()
}

impl Node {
    /// A node with no children yet (every lane empty).
    fn empty() -> Self {
        Self {
            pc: [Vec4::ZERO; 3],
            w: [Vec4::ZERO; 3],
            radius2: Vec4::ZERO,
            d2_floor: Vec4::ONE,
            phi: Vec4::ZERO,
            cos_o: Vec4::ONE,
            sin_o: Vec4::ZERO,
            // No cosine is above 2: an empty lane never emits.
            cos_e: Vec4::splat(2.0),
            two_sided: BVec4A::FALSE,
            child: [EMPTY; WIDTH],
        }
    }

    /// Sets lane `k` to child `r` of bounds `lb`.
    fn set(&mut self, k: usize, lb: &LightBounds, r: u32) {
        let diag = (lb.bounds.max - lb.bounds.min).length();
        let pc = lb.bounds.centroid();
        for a in 0..3 {
            self.pc[a][k] = pc[a];
            self.w[a][k] = lb.w[a];
        }
        self.radius2[k] = 0.25 * diag * diag;
        self.d2_floor[k] = (0.5 * diag).max(f32::MIN_POSITIVE);
        self.phi[k] = lb.phi;
        self.cos_o[k] = lb.cos_theta_o;
        self.sin_o[k] = safe_sqrt(1.0 - lb.cos_theta_o * lb.cos_theta_o);
        self.cos_e[k] = lb.cos_theta_e;
        self.two_sided.set(k, lb.two_sided);
        self.child[k] = r;
    }

    /// What each child sends toward `p` (surface normal `n`, or zero for
    /// none), up to a constant: see the module docs. Zero only where none of
    /// its lights can reach `p`; finite, never NaN, at most `f32::MAX / 8`
    /// (four add up without overflow). No branches: the angle tests go
    /// either way from one node to the next.
    #[inline]
    fn importance(&self, p: Vec3A, n: Vec3A) -> Vec4 {
        let t = [
            Vec4::splat(p.x) - self.pc[0],
            Vec4::splat(p.y) - self.pc[1],
            Vec4::splat(p.z) - self.pc[2],
        ];
        let dc2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
        let away = dc2.cmpgt(Vec4::ZERO);
        let inv_d = Vec4::select(away, dc2.sqrt().recip(), Vec4::ZERO);
        let wi = [t[0] * inv_d, t[1] * inv_d, t[2] * inv_d];
        // The box's bounding sphere seen from `p` (all directions from
        // inside it): θb.
        let inside = dc2.cmplt(self.radius2);
        let sin2 = (self.radius2 * inv_d * inv_d).min(Vec4::ONE);
        let sin_b = Vec4::select(inside, Vec4::ZERO, sin2.sqrt());
        let cos_b = Vec4::select(inside, Vec4::NEG_ONE, sqrt0(Vec4::ONE - sin2));
        let cos_w = self.w[0] * wi[0] + self.w[1] * wi[1] + self.w[2] * wi[2];
        let cos_w = Vec4::select(away, cos_w, Vec4::ONE);
        let cos_w = Vec4::select(self.two_sided, cos_w.abs(), cos_w);
        let sin_w = sqrt0(Vec4::ONE - cos_w * cos_w);
        // θ' = max(0, θw − θo − θb): the emission cone's nearest approach.
        let cos_x = cos_sub_clamped4(sin_w, cos_w, self.sin_o, self.cos_o);
        let sin_x = sin_sub_clamped4(sin_w, cos_w, self.sin_o, self.cos_o);
        let cos_p = cos_sub_clamped4(sin_x, cos_x, sin_b, cos_b);
        // The largest cosine the box can make with the surface normal.
        let cos_i = (wi[0] * n.x + wi[1] * n.y + wi[2] * n.z).abs().min(Vec4::ONE);
        let sin_i = sqrt0(Vec4::ONE - cos_i * cos_i);
        let cos_pi = if n == Vec3A::ZERO {
            Vec4::ONE
        } else {
            Vec4::select(away, cos_sub_clamped4(sin_i, cos_i, sin_b, cos_b), Vec4::ONE)
        };
        let importance = self.phi * cos_p * cos_pi / dc2.max(self.d2_floor);
        // Beyond θo + θe nothing is emitted toward `p`; `cmpgt` also sends
        // NaN to 0.
        let emits = cos_p.cmpgt(self.cos_e) & importance.cmpgt(Vec4::ZERO);
        Vec4::select(emits, importance.min(Vec4::splat(f32::MAX / 8.0)), Vec4::ZERO)
    }
}

impl Node {
    /// The children's importances and their sum, the one computation
    /// [`LightTree::pick`] and [`LightTree::pmf`] share (so their
    /// probabilities agree bit for bit); `None` when no child reaches `p`.
    #[inline]
    fn weights(&self, p: Vec3A, n: Vec3A) -> Option<([f32; WIDTH], f32)> {
        let imp = self.importance(p, n).to_array();
        let total: f32 = imp.iter().sum();
        (total > 0.0).then_some((imp, total))
    }
}

/// The share of picks made uniformly over all lights with power, whatever
/// the estimate says (the defensive part of the mixture; module docs).
/// Measured (64 spp, two-seed noise): on `tests/open_scenes.rs`' 36 scenes
/// the worst ratio to uniform selection is 1.008 at 0.1, 1.012 at 0.05
/// and 1.06 at 0 (before the sky's visibility was measured); on
/// `scenes/many_lights.ron` (64 lamps) it costs 6% of noise at 0.1 and 10%
/// at 0.2 against none.
pub const UNIFORM_SHARE: f32 = 0.1;

/// See the module docs.
#[derive(Clone, Debug)]
pub struct LightTree {
    nodes: Vec<Node>,
    /// Per light: its path from the root (two bits per level, the child slot
    /// taken) and depth, or `None` when it is not in the tree.
    trail: Vec<Option<(u64, u32)>>,
    /// The environment, if it has power: its light index and its irradiance
    /// by normal.
    env: Option<(u32, SkyWeight)>,
    /// The directional lights with power, weighed beside the tree.
    suns: Box<[Sun]>,
    /// The share of the sky's irradiance the scene's surfaces see
    /// (`integrators/sky_visibility.rs`); 1 until measured.
    sky_visibility: f32,
    /// Every light with power (the tree's, the environment and the
    /// directional lights), for the uniform part of the mixture.
    candidates: Vec<u32>,
    /// The tree holds one light and nothing beside it ever has weight (no
    /// directional light; no sky, or a constant one): the estimate picks
    /// that light wherever it is, without weighing it. See [`Self::top`].
    single: bool,
}

/// A directional light beside the tree: its index, the unit direction
/// toward it and π × its irradiance (luminance, W/m²).
#[derive(Clone, Copy, Debug)]
struct Sun {
    light: u32,
    toward: Vec3A,
    pi_e: f32,
}

impl Sun {
    /// π × the irradiance it gives a surface of normal `n` (either side, as
    /// the tree's `|cos|`), or π E at a point with no surface.
    #[inline]
    fn at(&self, n: Vec3A) -> f32 {
        if n == Vec3A::ZERO {
            self.pi_e
        } else {
            self.pi_e * n.dot(self.toward).abs()
        }
    }
}

impl LightTree {
    /// The tree over `lights`. `None` when there is nothing to choose per
    /// point (the caller then picks by power): fewer than two lights with
    /// power among the bounded ones, the sky and the directional lights.
    pub fn new(lights: &[Light]) -> Option<Self> {
        let mut items = Vec::new();
        let mut env = None;
        let mut suns = Vec::new();
        for (i, l) in lights.iter().enumerate() {
            // Bounded lights with power go in the tree; the first sky with
            // power and every directional light with power are weighed
            // beside it; the rest are never picked here.
            let bounds = light_bounds(l);
            if let Some(lb) =
                bounds.filter(|lb| lb.phi > 0.0 && lb.bounds.min.is_finite() && lb.bounds.max.is_finite())
            {
                items.push((i as u32, lb))
            } else if let (Some(e), None) = (l.as_environment(), &bounds)
                && luminance(e.power()) > 0.0
                && env.is_none()
            {
                env = Some((i as u32, *e.weight()))
            } else if let Some(d) = l.as_directional() {
                let pi_e = PI * luminance(d.irradiance);
                if pi_e > 0.0 && pi_e.is_finite() && d.direction.is_finite() {
                    suns.push(Sun {
                        light: i as u32,
                        toward: -d.direction,
                        pi_e: pi_e.min(f32::MAX / 16.0),
                    });
                }
            }
        }
        if items.len() + suns.len() + usize::from(env.is_some()) < 2 {
            return None;
        }
        let mut candidates: Vec<u32> = items
            .iter()
            .map(|it| it.0)
            .chain(env.map(|e| e.0))
            .chain(suns.iter().map(|s| s.light))
            .collect();
        candidates.sort_unstable();
        let single = items.len() == 1 && suns.is_empty() && env.as_ref().is_none_or(|e| e.1.is_flat());
        let mut tree = Self {
            nodes: Vec::with_capacity(items.len()),
            trail: vec![None; lights.len()],
            env,
            suns: suns.into_boxed_slice(),
            sky_visibility: 1.0,
            candidates,
            single,
        };
        if !items.is_empty() {
            tree.build(&mut items, 0, 0);
        }
        Some(tree)
    }

    /// Appends the node over `items` (at least two; depth `depth`, path
    /// `bits`) and its subtrees; returns their bounds. Each node splits its
    /// lights in four by two median splits, each along the longest axis of
    /// its part's centroids; a part of one light is a leaf (a root over one
    /// light has one child).
    fn build(&mut self, items: &mut [(u32, LightBounds)], bits: u64, depth: u32) -> LightBounds {
        debug_assert!(!items.is_empty() && depth < 32);
        let at = self.nodes.len();
        self.nodes.push(Node::empty());
        let n = items.len();
        let mut parts: Vec<&mut [(u32, LightBounds)]> = Vec::with_capacity(WIDTH);
        if n <= WIDTH {
            parts.extend(items.chunks_mut(1));
        } else {
            median_split(items);
            let (left, right) = items.split_at_mut(n / 2);
            for half in [left, right] {
                median_split(half);
                let m = half.len() / 2;
                let (a, b) = half.split_at_mut(m);
                parts.push(a);
                parts.push(b);
            }
        }
        let mut union: Option<LightBounds> = None;
        for (k, part) in parts.into_iter().enumerate() {
            let path = bits | (k as u64) << (2 * depth);
            let (lb, r) = if let [(light, lb)] = part {
                self.trail[*light as usize] = Some((path, depth + 1));
                (*lb, LEAF | *light)
            } else {
                let child = self.nodes.len() as u32;
                (self.build(part, path, depth + 1), child)
            };
            self.nodes[at].set(k, &lb, r);
            union = Some(union.map_or(lb, |u| u.union(&lb)));
        }
        union.unwrap_or(items[0].1)
    }

    /// Scales the environment's importance by `v` ∈ (0, 1], the measured
    /// share of its irradiance that surfaces see (ignored otherwise).
    pub fn set_sky_visibility(&mut self, v: f32) {
        if v > 0.0 && v <= 1.0 {
            self.sky_visibility = v;
        }
    }

    /// The estimate's first choice at `p`, `n`: the environment's importance
    /// and the root's children's (with their sum), the one computation
    /// [`Self::pick`] and [`Self::pmf`] share, so their probabilities agree
    /// bit for bit.
    ///
    /// A tree of one light beside a constant sky (one area light and an
    /// ambient sky: `textured_spheres`, a common studio setup) skips the
    /// weighing: the sky's weight is zero everywhere, so the estimate's
    /// only question was whether the light's importance is zero at `p`
    /// (behind a one-sided emitter, outside a spot's cone), and its light
    /// sample answers that as cheaply (it returns nothing there). The
    /// root's SIMD importance was 8% of that scene's time (perf); the
    /// probabilities are unchanged wherever the light can reach `p`.
    #[inline]
    pub fn top(&self, p: Vec3A, n: Vec3A) -> Top {
        if self.single {
            return (0.0, Some(([1.0, 0.0, 0.0, 0.0], 1.0)));
        }
        let mut env = self.env.as_ref().map_or(0.0, |e| self.sky_visibility * e.1.at(n));
        for sun in self.suns.iter() {
            env += sun.at(n);
        }
        let env = if env.is_finite() {
            env.min(f32::MAX / 8.0)
        } else {
            0.0
        };
        (env, self.nodes.first().and_then(|root| root.weights(p, n)))
    }

    /// The sky's weight at a point of normal `n` (as [`Self::top`] sums it).
    #[inline]
    fn sky_at(&self, n: Vec3A) -> f32 {
        let w = self.env.as_ref().map_or(0.0, |e| self.sky_visibility * e.1.at(n));
        if w.is_finite() { w.min(f32::MAX / 8.0) } else { 0.0 }
    }

    /// The uniform part of every candidate's probability.
    #[inline]
    fn uniform_pmf(&self) -> f32 {
        UNIFORM_SHARE / self.candidates.len() as f32
    }

    /// A light and its probability for a shading point `p` with normal `n`
    /// (zero: none), from `u` ∈ [0, 1); `None` when the estimate's walk
    /// ends where no light can reach `p`.
    pub fn pick(&self, p: Vec3A, n: Vec3A, u: f32) -> Option<(usize, f32)> {
        self.pick_from(&self.top(p, n), p, n, u)
    }

    /// [`Self::pick`] with `top` = [`Self::top`]`(p, n)` made already.
    pub fn pick_from(&self, top: &Top, p: Vec3A, n: Vec3A, u: f32) -> Option<(usize, f32)> {
        if u < UNIFORM_SHARE {
            let k = ((u / UNIFORM_SHARE) * self.candidates.len() as f32) as usize;
            let i = self.candidates[k.min(self.candidates.len() - 1)] as usize;
            let pmf = self.pmf_from(top, p, n, i);
            return (pmf > 0.0).then_some((i, pmf));
        }
        let mut u = ((u - UNIFORM_SHARE) / (1.0 - UNIFORM_SHARE)).clamp(0.0, ONE_MINUS_EPSILON);
        let (env, root) = *top;
        let root_total = root.map_or(0.0, |r| r.1);
        let sum = env + root_total;
        if sum.is_nan() || sum <= 0.0 {
            return None;
        }
        if u * sum < env {
            // The sky or a directional light, in proportion to their
            // weights here (the sky's alone when there is no sun).
            if self.suns.is_empty() {
                let (i, _) = self.env?;
                return Some((i as usize, self.uniform_pmf() + (1.0 - UNIFORM_SHARE) * env / sum));
            }
            let target = u * sum;
            let mut acc = self.sky_at(n);
            let mut chosen = self.env.filter(|_| target < acc).map(|e| (e.0, acc));
            if chosen.is_none() {
                let mut last = None;
                for sun in self.suns.iter() {
                    let w = sun.at(n);
                    if w > 0.0 {
                        last = Some((sun.light, w));
                        if target < acc + w {
                            break;
                        }
                    }
                    acc += w;
                }
                // Rounding past the end: the last with any weight.
                chosen = last.or(self.env.map(|e| (e.0, self.sky_at(n))));
            }
            let (i, w) = chosen?;
            return (w > 0.0).then(|| (i as usize, self.uniform_pmf() + (1.0 - UNIFORM_SHARE) * w / sum));
        }
        let (mut imp, mut total) = root?;
        u = ((u * sum - env) / root_total).clamp(0.0, ONE_MINUS_EPSILON);
        let mut pmf = root_total / sum;
        let mut at = 0usize;
        loop {
            // The child whose share of `total` holds `u · total`; the last
            // one with any share if rounding runs past the end.
            let target = u * total;
            let (mut k, mut acc) = (0, 0.0f32);
            for (j, &i) in imp.iter().enumerate() {
                if i > 0.0 {
                    k = j;
                    if target < acc + i {
                        break;
                    }
                    acc += i;
                }
            }
            let below: f32 = imp[..k].iter().sum();
            pmf *= imp[k] / total;
            u = ((target - below) / imp[k]).clamp(0.0, ONE_MINUS_EPSILON);
            let r = self.nodes[at].child[k];
            if r & LEAF != 0 {
                let i = (r & !LEAF) as usize;
                return Some((i, self.uniform_pmf() + (1.0 - UNIFORM_SHARE) * pmf));
            }
            at = r as usize;
            (imp, total) = self.nodes[at].weights(p, n)?;
        }
    }

    /// The probability that [`Self::pick`] from `p`, `n` returns light `i`.
    pub fn pmf(&self, p: Vec3A, n: Vec3A, i: usize) -> f32 {
        self.pmf_from(&self.top(p, n), p, n, i)
    }

    /// [`Self::pmf`] with `top` = [`Self::top`]`(p, n)` made already.
    pub fn pmf_from(&self, top: &Top, p: Vec3A, n: Vec3A, i: usize) -> f32 {
        // A candidate is in the tree or is the sky.
        let in_tree = self.trail.get(i).is_some_and(Option::is_some);
        if !in_tree
            && self.env.is_none_or(|e| e.0 as usize != i)
            && !self.suns.iter().any(|s| s.light as usize == i)
        {
            return 0.0;
        }
        self.uniform_pmf() + (1.0 - UNIFORM_SHARE) * self.estimate_pmf(top, p, n, i)
    }

    /// The estimate's probability of light `i` at `p`, `n` (the mixture's
    /// other part), from `top` = [`Self::top`]`(p, n)`.
    fn estimate_pmf(&self, top: &Top, p: Vec3A, n: Vec3A, i: usize) -> f32 {
        let (env, root) = *top;
        let root_total = root.map_or(0.0, |r| r.1);
        let sum = env + root_total;
        if sum.is_nan() || sum <= 0.0 {
            return 0.0;
        }
        if self.env.is_some_and(|e| e.0 as usize == i) {
            return if self.suns.is_empty() { env } else { self.sky_at(n) } / sum;
        }
        if let Some(sun) = self.suns.iter().find(|s| s.light as usize == i) {
            return sun.at(n) / sum;
        }
        let (Some(Some((bits, depth))), Some((mut imp, mut total))) = (self.trail.get(i).copied(), root)
        else {
            return 0.0;
        };
        let mut pmf = root_total / sum;
        let mut at = 0usize;
        for level in 0..depth {
            if level > 0 {
                let Some(w) = self.nodes[at].weights(p, n) else {
                    return 0.0;
                };
                (imp, total) = w;
            }
            let k = (bits >> (2 * level) & 3) as usize;
            pmf *= imp[k] / total;
            at = self.nodes[at].child[k] as usize;
        }
        pmf
    }

    /// Number of nodes (statistics, tests).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
}

/// Reorders `items` so that the first half has the smaller centroids along
/// the longest axis of their centroids' bounds.
fn median_split(items: &mut [(u32, LightBounds)]) {
    let centroids = items
        .iter()
        .fold(Aabb::EMPTY, |acc, (_, lb)| acc.grow_point(lb.bounds.centroid()));
    let extent = centroids.max - centroids.min;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    if mid > 0 {
        items.select_nth_unstable_by(mid, |a, b| {
            a.1.bounds.centroid()[axis].total_cmp(&b.1.bounds.centroid()[axis])
        });
    }
}

/// The largest f32 below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lights::{PointLight, QuadLight, SphereLight};
    use crate::math::{Pcg32, Rgb};

    fn quad(at: Vec3A, facing_down: bool, radiance: f32) -> Light {
        let (u, v) = if facing_down {
            (Vec3A::new(0.2, 0.0, 0.0), Vec3A::new(0.0, 0.0, 0.2))
        } else {
            (Vec3A::new(0.0, 0.0, 0.2), Vec3A::new(0.2, 0.0, 0.0))
        };
        Light::Quad(QuadLight::new(at, u, v, Rgb::splat(radiance)))
    }

    /// A mix of lights: quads facing down and up, points, spheres.
    fn lights() -> Vec<Light> {
        let mut rng = Pcg32::new(3, 7);
        let mut v = Vec::new();
        for k in 0..40 {
            let at = Vec3A::new(
                rng.next_f32() * 20.0 - 10.0,
                rng.next_f32() * 4.0,
                rng.next_f32() * 20.0 - 10.0,
            );
            v.push(match k % 4 {
                0 => quad(at, true, 1.0 + rng.next_f32()),
                1 => quad(at, false, 5.0),
                2 => Light::Point(PointLight {
                    position: at,
                    intensity: Rgb::splat(rng.next_f32()),
                }),
                _ => Light::Sphere(SphereLight {
                    texture: None,
                    mitsuba_uv: false,
                    center: at,
                    radius: 0.3,
                    radiance: Rgb::splat(2.0),
                    two_sided: false,
                }),
            });
        }
        v
    }

    /// A random point around [`lights`]'s and a random normal.
    fn shading_point(rng: &mut Pcg32) -> (Vec3A, Vec3A) {
        let p = Vec3A::new(
            rng.next_f32() * 24.0 - 12.0,
            rng.next_f32() * 6.0 - 1.0,
            rng.next_f32() * 24.0 - 12.0,
        );
        (p, crate::math::sampling::uniform_sphere(rng.next_vec2()))
    }

    #[test]
    fn picks_sum_to_one_and_match_the_pmf() {
        let lights = lights();
        let tree = LightTree::new(&lights).expect("a tree");
        assert!(tree.node_count() < lights.len());
        let mut rng = Pcg32::new(9, 1);
        for _ in 0..200 {
            let (p, n) = shading_point(&mut rng);
            let total: f64 = (0..lights.len()).map(|i| tree.pmf(p, n, i) as f64).sum();
            // At most 1: a subtree none of whose lights reach `p` may still
            // have been chosen (its parent's looser bounds did), and then
            // no light is sampled, which loses nothing that contributes.
            assert!(total <= 1.0 + 1e-4 && total > 0.5, "pmfs sum to {total} at {p}");
            for _ in 0..20 {
                if let Some((i, pmf)) = tree.pick(p, n, rng.next_f32()) {
                    let want = tree.pmf(p, n, i);
                    assert!(pmf > 0.0);
                    assert!(
                        (pmf - want).abs() <= 1e-6 * want.max(1.0),
                        "pick {pmf}, pmf {want}"
                    );
                }
            }
        }
    }

    /// Directional lights are weighed beside the tree and the sky: picks
    /// and densities agree, they sum to one where the tree's lights all
    /// reach, each sun's share follows the irradiance it gives the surface,
    /// and a scene of suns alone (no tree) still picks per point.
    #[test]
    fn directional_lights_are_weighed_beside_the_tree_and_the_sky() {
        use crate::lights::{DirectionalLight, EnvironmentLight};
        let sun = |d: Vec3A, e: f32| Light::Directional(DirectionalLight::new(d, Rgb::splat(e)));
        let mixes: Vec<Vec<Light>> = vec![
            // Lamps, a map sky and two suns.
            {
                let mut v = lights();
                v.push(Light::Environment(Box::new(overhead_sun(1.0))));
                v.push(sun(Vec3A::new(0.3, -1.0, 0.2), 3.0));
                v.push(sun(Vec3A::new(-1.0, -0.2, 0.0), 1.0));
                v
            },
            // One lamp and one sun: a tree of one light and a sun.
            vec![quad(Vec3A::new(0.0, 3.0, 0.0), true, 5.0), sun(Vec3A::NEG_Y, 2.0)],
            // Suns and a constant sky only: no tree nodes at all.
            vec![
                sun(Vec3A::NEG_Y, 2.0),
                Light::Environment(Box::new(EnvironmentLight::constant(Rgb::splat(0.5)))),
                sun(Vec3A::X, 1.0),
            ],
        ];
        let mut rng = Pcg32::new(5, 11);
        for lights in &mixes {
            let tree = LightTree::new(lights).expect("a tree");
            for _ in 0..300 {
                let (p, n) = shading_point(&mut rng);
                let n = if rng.next_f32() < 0.1 { Vec3A::ZERO } else { n };
                let total: f64 = (0..lights.len()).map(|i| tree.pmf(p, n, i) as f64).sum();
                assert!(total <= 1.0 + 1e-4 && total > 0.5, "pmfs sum to {total} at {p}");
                for _ in 0..20 {
                    if let Some((i, pmf)) = tree.pick(p, n, rng.next_f32()) {
                        let want = tree.pmf(p, n, i);
                        assert!(
                            pmf > 0.0 && (pmf - want).abs() <= 1e-6 * want.max(1.0),
                            "pick {pmf}, pmf {want}"
                        );
                    }
                }
            }
        }
        // Facing the first sun, the second (grazing) gets only the uniform share.
        let lights = &mixes[2];
        let tree = LightTree::new(lights).expect("a tree");
        let up = Vec3A::Y;
        let (a, b) = (tree.pmf(Vec3A::ZERO, up, 0), tree.pmf(Vec3A::ZERO, up, 2));
        assert!((b - UNIFORM_SHARE / 3.0).abs() < 1e-6, "grazing sun {b}");
        assert!(
            (a - (UNIFORM_SHARE / 3.0 + 1.0 - UNIFORM_SHARE)).abs() < 1e-5,
            "facing sun {a}"
        );
        // Half way between them both are weighed by E cos θ: 2 · 0.707 against 1 · 0.707.
        let n = Vec3A::new(-1.0, 1.0, 0.0).normalize();
        let (a, b) = (tree.pmf(Vec3A::ZERO, n, 0), tree.pmf(Vec3A::ZERO, n, 2));
        let share = |x: f32| x - UNIFORM_SHARE / 3.0;
        assert!((share(a) / share(b) - 2.0).abs() < 1e-4, "{a} against {b}");
        // A single sun and nothing else: nothing to choose, no tree.
        assert!(LightTree::new(&[sun(Vec3A::NEG_Y, 1.0)]).is_none());
    }

    /// A light that reaches a point is never given probability zero there:
    /// the estimate would lose it (bias).
    #[test]
    fn a_light_that_reaches_a_point_has_probability() {
        let lights = lights();
        let tree = LightTree::new(&lights).expect("a tree");
        let mut rng = Pcg32::new(4, 4);
        for _ in 0..2000 {
            let (p, n) = shading_point(&mut rng);
            for (i, l) in lights.iter().enumerate() {
                for _ in 0..4 {
                    let Some(ls) = l.sample(
                        p,
                        n,
                        rng.next_vec2(),
                        crate::sampler::Draw::Independent,
                        &crate::geometry::Geometry::default(),
                    ) else {
                        continue;
                    };
                    let reaches = ls.li != Rgb::ZERO && ls.wi.dot(n).abs() > 1e-3 && ls.pdf > 0.0;
                    if reaches {
                        assert!(
                            tree.pmf(p, n, i) > 0.0,
                            "light {i} reaches {p} (n {n}) with pmf 0"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_near_light_is_preferred_and_one_facing_away_keeps_only_the_floor() {
        // A point under one down-facing quad, far from another; a third
        // quad just above faces up (away from the point).
        let lights = vec![
            quad(Vec3A::new(-0.1, 1.0, -0.1), true, 1.0),
            quad(Vec3A::new(50.0, 1.0, 0.0), true, 1.0),
            quad(Vec3A::new(-0.1, 0.5, -0.1), false, 1.0),
        ];
        let tree = LightTree::new(&lights).expect("a tree");
        let (p, n) = (Vec3A::ZERO, Vec3A::Y);
        let floor = UNIFORM_SHARE / 3.0;
        assert!(
            tree.pmf(p, n, 0) > floor + (1.0 - UNIFORM_SHARE) * 0.99,
            "near light {}",
            tree.pmf(p, n, 0)
        );
        assert_eq!(tree.pmf(p, n, 2), floor);
        let away = (0..1000)
            .filter(|k| tree.pick(p, n, (*k as f32 + 0.5) / 1000.0).expect("a light").0 == 2)
            .count();
        assert!((28..=38).contains(&away), "picked {away} times in 1000");
    }

    /// A sky map (64 × 32) whose two top rows, a sun about 6° across
    /// straight above, hold radiance `strength`; black elsewhere.
    fn overhead_sun(strength: f32) -> crate::lights::EnvironmentLight {
        let (w, h) = (64u32, 32u32);
        let rgb: Vec<f32> = (0..w * h)
            .flat_map(|k| [if k < 2 * w { 1.0 } else { 0.0 }; 3])
            .collect();
        crate::lights::EnvironmentLight::from_map(crate::lights::EnvMap::from_rgb(w, h, &rgb), strength, 0.0)
    }

    /// Area lights beside an environment: what the sky gets follows what it
    /// sends to the point, not the scene's size; near a bright lamp the sky
    /// gets little beyond the uniform floor, far from every lamp nearly all.
    #[test]
    fn the_environment_is_weighed_by_what_it_sends_to_the_point() {
        // A small sun straight above (weighed in full, see `SkyWeight`).
        let unit = overhead_sun(1.0).weight().at(Vec3A::Y);
        for sky in [0.01f32, 0.2, 1.0] {
            // Sends π·sky to a point facing up, as a constant sky of
            // radiance `sky` would: weighs π × that.
            let strength = PI * PI * sky / unit;
            let mut env = overhead_sun(strength);
            // A 400-unit scene: by power the sky would take nearly every pick.
            env.scene_radius = 400.0;
            let lights = vec![
                quad(Vec3A::new(-0.1, 1.0, -0.1), true, 50.0),
                Light::Environment(Box::new(env)),
            ];
            let tree = LightTree::new(&lights).expect("a tree");
            let floor = UNIFORM_SHARE / 2.0;
            let near = tree.pmf(Vec3A::ZERO, Vec3A::Y, 1);
            let weight = tree.top(Vec3A::ZERO, Vec3A::Y).0;
            assert!((weight - PI * PI * sky).abs() < 1e-3 * weight, "{weight}");
            let far = tree.pmf(Vec3A::new(300.0, 0.0, 0.0), Vec3A::Y, 1);
            // Under the lamp its irradiance is 50 · 0.04 / 1 = 2 against the sky's π·sky.
            let share = PI * sky / (PI * sky + 2.0);
            assert!(
                (near - (floor + (1.0 - UNIFORM_SHARE) * share)).abs() < 0.05,
                "sky {sky}: {near} near the lamp"
            );
            assert!(
                far > floor + (1.0 - UNIFORM_SHARE) * 0.99,
                "sky {sky}: {far} far from the lamp"
            );
            let total = tree.pmf(Vec3A::ZERO, Vec3A::Y, 0) + near;
            assert!((total - 1.0).abs() < 1e-5, "{total}");
        }
    }

    /// A constant sky is left to BSDF sampling, which finds it with no
    /// variance on a surface it lights: beside a lamp, however dim the lamp
    /// or far the point, it keeps the uniform share of the picks and no
    /// more.
    #[test]
    fn a_constant_sky_keeps_only_the_uniform_share() {
        use crate::lights::EnvironmentLight;
        for sky in [0.01f32, 1.0, 100.0] {
            let lights = vec![
                quad(Vec3A::new(-0.1, 1.0, -0.1), true, 50.0),
                Light::Environment(Box::new(EnvironmentLight::constant(Rgb::splat(sky)))),
            ];
            let tree = LightTree::new(&lights).expect("a tree");
            for p in [Vec3A::ZERO, Vec3A::new(300.0, 0.0, 0.0)] {
                let pmf = tree.pmf(p, Vec3A::Y, 1);
                assert!(
                    (pmf - UNIFORM_SHARE / 2.0).abs() < 1e-3,
                    "sky {sky} at {p}: {pmf}"
                );
            }
        }
    }

    /// One lamp beside a constant sky (or a point light, a sphere: any one
    /// bounded light) skips the weighing: picks and densities still agree
    /// and sum to one, the sky keeps its uniform share, and wherever the
    /// lamp reaches the point the probabilities are the weighed tree's. A
    /// second lamp, a map sky or a sun turns the weighing back on.
    #[test]
    fn one_lamp_beside_a_constant_sky_is_picked_without_weighing() {
        use crate::lights::{DirectionalLight, EnvironmentLight};
        let sky = || Light::Environment(Box::new(EnvironmentLight::constant(Rgb::splat(0.3))));
        let mut rng = Pcg32::new(5, 11);
        for lamp in lights().into_iter().take(4) {
            let lights = vec![lamp.clone(), sky()];
            let tree = LightTree::new(&lights).expect("a tree");
            assert!(tree.single);
            // The same tree, weighed.
            let weighed = LightTree {
                single: false,
                ..tree.clone()
            };
            for _ in 0..500 {
                let (p, n) = shading_point(&mut rng);
                let pmfs = [tree.pmf(p, n, 0), tree.pmf(p, n, 1)];
                assert!((pmfs[0] + pmfs[1] - 1.0).abs() < 1e-6, "{pmfs:?}");
                assert!((pmfs[1] - UNIFORM_SHARE / 2.0).abs() < 1e-6, "the sky: {pmfs:?}");
                if weighed.pmf(p, n, 0) > UNIFORM_SHARE / 2.0 {
                    // The lamp reaches `p`: nothing changed.
                    assert_eq!(weighed.pmf(p, n, 0), pmfs[0]);
                    assert_eq!(weighed.pmf(p, n, 1), pmfs[1]);
                }
                let u = rng.next_f32();
                let (i, pmf) = tree.pick(p, n, u).expect("always a light");
                assert_eq!(pmf, pmfs[i]);
            }
        }
        let sun = Light::Directional(DirectionalLight::new(-Vec3A::Y, Rgb::splat(1.0)));
        let lamp = quad(Vec3A::new(0.0, 1.0, 0.0), true, 5.0);
        for others in [
            vec![quad(Vec3A::new(2.0, 1.0, 0.0), true, 5.0), sky()],
            vec![Light::Environment(Box::new(overhead_sun(1.0)))],
            vec![sun, sky()],
        ] {
            let lights: Vec<Light> = std::iter::once(lamp.clone()).chain(others).collect();
            assert!(!LightTree::new(&lights).expect("a tree").single);
        }
    }

    /// Every kind of lamp beside a sun, each sending a point facing it
    /// the same irradiance as the sky: each takes half the picks the
    /// estimate makes. With powers, a sphere or a point lamp took four
    /// fifths (its power is four times π × what it sends one way), a
    /// two-sided quad two thirds, a spot `1/(1 − cos θ)` times its share.
    #[test]
    fn every_kind_of_lamp_is_weighed_in_the_skys_units() {
        use crate::lights::SpotLight;
        // A sun straight above, and what it weighs at a point facing up:
        // the irradiance `e` a lamp must match.
        let sun = overhead_sun(1e3);
        let e = sun.weight().at(Vec3A::Y) / PI;
        assert!(
            e > 0.9 * sun.weight().irradiance.at(Vec3A::Y),
            "a sun is weighed in full"
        );
        // A lamp 10 units above the point.
        let (d, at) = (10.0f32, Vec3A::new(0.0, 10.0, 0.0));
        let mut two_sided = QuadLight::new(
            at - Vec3A::new(0.05, 0.0, 0.05),
            Vec3A::new(0.1, 0.0, 0.0),
            Vec3A::new(0.0, 0.0, 0.1),
            Rgb::splat(e * d * d / 0.01),
        );
        two_sided.two_sided = true;
        let lamps = [
            // E = I / d².
            Light::Point(PointLight {
                position: at,
                intensity: Rgb::splat(e * d * d),
            }),
            // E = L·πr² / d² for a small sphere.
            Light::Sphere(SphereLight::new(at, 0.05, Rgb::splat(e * d * d / (PI * 0.0025)))),
            // Facing down, E = L·A / d².
            quad(at - Vec3A::new(0.1, 0.0, 0.1), true, e * d * d / 0.04),
            Light::Quad(two_sided),
            Light::Spot(SpotLight::new(
                at,
                Vec3A::NEG_Y,
                Rgb::splat(e * d * d),
                60.0,
                10.0,
            )),
        ];
        for lamp in lamps {
            let what = format!("{lamp:?}");
            let lights = vec![lamp, Light::Environment(Box::new(sun.clone()))];
            let tree = LightTree::new(&lights).expect("a tree");
            let sky_pmf = tree.pmf(Vec3A::ZERO, Vec3A::Y, 1);
            let want = UNIFORM_SHARE / 2.0 + (1.0 - UNIFORM_SHARE) * 0.5;
            assert!(
                (sky_pmf - want).abs() < 0.01,
                "sky {sky_pmf}, not {want}, beside {what}"
            );
        }
    }

    /// Lights stacked at one point (no axis to split along), a huge and a
    /// tiny one, and points at the shading point itself: picks and pmfs
    /// still agree, stay finite and sum to at most one.
    #[test]
    fn degenerate_layouts_stay_consistent() {
        let at = Vec3A::new(1.0, 2.0, 3.0);
        let mut lights: Vec<Light> = (0..9)
            .map(|k| {
                Light::Point(PointLight {
                    position: at,
                    intensity: Rgb::splat(1.0 + k as f32),
                })
            })
            .collect();
        lights.push(quad(Vec3A::new(-1e6, 5.0, -1e6), true, 1e-3));
        lights.push(Light::Sphere(SphereLight {
            texture: None,
            mitsuba_uv: false,
            center: Vec3A::ZERO,
            radius: 1e-6,
            radiance: Rgb::splat(1e6),
            two_sided: false,
        }));
        let tree = LightTree::new(&lights).expect("a tree");
        for p in [at, Vec3A::ZERO, Vec3A::new(0.0, -3.0, 0.0), Vec3A::splat(1e7)] {
            for n in [Vec3A::ZERO, Vec3A::Y, -Vec3A::X] {
                let total: f32 = (0..lights.len()).map(|i| tree.pmf(p, n, i)).sum();
                assert!(
                    total.is_finite() && total <= 1.0 + 1e-4,
                    "sum {total} at {p}, {n}"
                );
                for k in 0..64 {
                    if let Some((i, pmf)) = tree.pick(p, n, (k as f32 + 0.5) / 64.0) {
                        assert!(pmf.is_finite() && pmf > 0.0 && pmf <= 1.0);
                        assert!((pmf - tree.pmf(p, n, i)).abs() <= 1e-6, "light {i} at {p}");
                    }
                }
            }
        }
    }

    #[test]
    fn cone_union_holds_both_cones() {
        let mut rng = Pcg32::new(1, 2);
        for _ in 0..2000 {
            let a = (
                crate::math::sampling::uniform_sphere(rng.next_vec2()),
                rng.next_f32() * 2.0 - 1.0,
            );
            let b = (
                crate::math::sampling::uniform_sphere(rng.next_vec2()),
                rng.next_f32() * 2.0 - 1.0,
            );
            let (w, cos_o) = cone_union(a, b);
            for (axis, cos_c) in [a, b] {
                // The cone's edge directions within the union.
                let theta = axis.dot(w).clamp(-1.0, 1.0).acos() + cos_c.clamp(-1.0, 1.0).acos();
                assert!(
                    theta.min(PI) <= cos_o.clamp(-1.0, 1.0).acos() + 1e-3,
                    "{a:?} ∪ {b:?} = {w}, {cos_o}"
                );
            }
        }
    }
}
