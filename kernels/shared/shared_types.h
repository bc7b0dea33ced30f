/* Struct layouts shared by the host (C++) and the kernels (OpenCL C): each layout exists once, here.
 * Only 4-byte scalars and arrays of them (and 8-byte ulong at multiples of 8), so both compilers
 * lay them out identically without the 16-byte alignment that float3 has in OpenCL. */
#ifndef KASHA_SHARED_TYPES_H
#define KASHA_SHARED_TYPES_H

#ifndef __OPENCL_VERSION__
#include <cstdint>
namespace kasha {
typedef std::uint32_t uint;
typedef std::uint64_t ulong;
#define KASHA_STATIC_SIZE(T, bytes) static_assert(sizeof(T) == (bytes), #T " layout changed")
/* Headers that host and kernels share: global pointers are plain pointers on the host, and sums
 * are carried in double there. */
#define KASHA_GLOBAL
typedef double kasha_real;
#else
#define KASHA_STATIC_SIZE(T, bytes)
#define KASHA_GLOBAL __global
typedef float kasha_real;
#endif

/* Next-event estimation samples a triangle by solid angle between these (steradians), by area
 * outside: below, Arvo's construction in float lands points up to 1e-4 (barycentric) off small
 * triangles on some devices (seen at 1.3e-3 sr on an NVIDIA H100) while area sampling is as good
 * there; above, the triangle nearly fills the hemisphere (pbrt-v4's bound). */
#define KASHA_MIN_SPHERICAL_SOLID_ANGLE 1e-2f
#define KASHA_MAX_SPHERICAL_SOLID_ANGLE 6.22f

/* A guard on path length in every kernel, far beyond what Russian roulette reaches (a path of a
 * scene keeping 99.99 % of its light passes it with probability e^-26); what it cuts is counted
 * and reported. Kernels are built with the render's --depth-guard in its place. */
#ifndef KASHA_MAX_PATH_DEPTH
#define KASHA_MAX_PATH_DEPTH (1 << 18)
#endif

/* KASHA_DEPTH_CAP, defined only under --max-depth N (render/depth_cap.h): pbrt-v4's maxdepth, a
 * biased cap. A light path counts only with at most N scattering vertices (every vertex but the
 * camera's and the light's: a fluorescent, gloss or delta bounce is one); 0 keeps emitters seen
 * directly, 1 direct light. Left undefined, the kernels are the unbiased ones, unchanged. */

/* The BVH that Embree builds and the OpenCL traversal reads (kernels/geometry/bvh_traversal.h). Children
 * per node and triangles per leaf: one float8 expression tests all of a node's child boxes, or all
 * of a leaf's triangles (PoCL keeps float8 arithmetic as AVX instructions). */
#define KASHA_BVH_WIDTH 8
#define KASHA_BVH_LEAF_SIZE 8
/* The deepest BVH the builder may make, in levels of interior nodes (a million triangles take
 * about 10). A visit pushes at most KASHA_BVH_WIDTH - 1 children: the traversal's stack size. */
#define KASHA_BVH_MAX_DEPTH 32
#define KASHA_BVH_STACK ((KASHA_BVH_WIDTH - 1) * KASHA_BVH_MAX_DEPTH + 1)

/* An interior node, its children's boxes stored axis by axis (rows lo x, hi x, lo y, hi y, lo z,
 * hi z; one float per child) so that one node fetch tests all of them. child[i] >= 0 is an
 * interior node, < 0 the leaf ~child[i]. An unused slot has the empty box lo = +inf, hi = -inf,
 * which no ray enters. Node 0 is the root, always an interior node. */
typedef struct {
  float bounds[6][KASHA_BVH_WIDTH];
  int child[KASHA_BVH_WIDTH];
  int pad[KASHA_BVH_WIDTH]; /* to 256 bytes: a node spans four whole cache lines */
} KBvhNode;
KASHA_STATIC_SIZE(KBvhNode, 256);

/* A leaf's triangles, precomputed for Möller–Trumbore and stored coordinate by coordinate: v0,
 * e1 = v1 - v0, e2 = v2 - v0 (rows x, y, z; one float per triangle). tri[i] is the triangle's
 * index in leaf order (the KTriangle array), -1 for an unused slot, whose zero edges no ray hits. */
typedef struct {
  float v0[3][KASHA_BVH_LEAF_SIZE];
  float e1[3][KASHA_BVH_LEAF_SIZE];
  float e2[3][KASHA_BVH_LEAF_SIZE];
  int tri[KASHA_BVH_LEAF_SIZE];
} KBvhLeaf;
KASHA_STATIC_SIZE(KBvhLeaf, 320);

/* A triangle in BVH leaf order. `prim` is its index in scene order (what Embree reports as primID);
 * `emitter` indexes the emitter table, -1 when the triangle does not emit. */
typedef struct {
  float v0[3];
  float v1[3];
  float v2[3];
  int material;
  int emitter;
  int prim;
} KTriangle;
KASHA_STATIC_SIZE(KTriangle, 48);

/* A ray segment [tmin, tmax]. */
typedef struct {
  float org[3];
  float tmin;
  float dir[3];
  float tmax;
} KRay;
KASHA_STATIC_SIZE(KRay, 32);

/* Closest hit: prim == -1 for a miss; (u, v) are barycentrics of v1 and v2; `instance` is the
 * KInstance the triangle was met in (-1: the scene's own triangles, or a scene without instances). */
typedef struct {
  float t;
  int prim;
  float u;
  float v;
  int instance;
} KHit;
KASHA_STATIC_SIZE(KHit, 20);

/* A triangle's ∂p/∂u as pbrt-v4 derives it from its texture coordinates (in object space for an
 * instanced object's): the x axis of an anisotropic roughness (materials/surface.h). Per leaf
 * triangle, only where some used rough material is anisotropic (KASHA_ANISOTROPIC) or some used
 * material has a normal map (KASHA_NORMAL_MAPS: the x axis of its tangent frame). */
typedef struct {
  float dpdu[3];
  float pad;
} KTangent;
KASHA_STATIC_SIZE(KTangent, 16);

/* An object placed in the scene (pbrt-v4's ObjectInstance, docs/formats.md#instances): the
 * object's triangles and BVH are stored once, and each instance is a leaf of a top-level BVH over
 * the instances' boxes. A ray enters an instance transformed into object space, its direction
 * not renormalised, so distances along it are the same numbers in both spaces. Only built where
 * a scene has instances (KASHA_INSTANCES); the scene's own triangles are then instance 0 under
 * the identity. Matrices are 3 × 4 affine, row-major. */
typedef struct {
  float object_from_world[12];
  float world_from_object[12];
  int root;   /* the object's BVH root node */
  int object; /* the scene's object it places (-1: the scene's own triangles) */
  int mirrors; /* 1: the transform mirrors, so a placed triangle's winding turns its normal to the
                * back and the front is the other side (as a mirrored shape's is, flattened) */
  int pad;
} KInstance;
KASHA_STATIC_SIZE(KInstance, 112);

/* Pixel filters (geometry/pixel_filter.h): the unit box of kasha's own scenes, then pbrt-v4's box
 * and triangle of any radius, and the other filters as a table of 16 bins per half axis. */
#define KASHA_FILTER_PIXEL 0
#define KASHA_FILTER_BOX 1
#define KASHA_FILTER_TRIANGLE 2
#define KASHA_FILTER_TABLE 3
#define KASHA_FILTER_BINS 16
#define KASHA_FILTER_MAX_RADIUS 8

/* The camera (geometry/camera.h): pbrt-v4's perspective (a pinhole, or a thin lens of radius
 * lens_radius focused at focal_distance), orthographic and spherical cameras. */
#define KASHA_CAMERA_PERSPECTIVE 0
#define KASHA_CAMERA_ORTHOGRAPHIC 1
#define KASHA_CAMERA_EQUAL_AREA 2      /* spherical, pbrt-v4's equal-area square (its default) */
#define KASHA_CAMERA_EQUIRECTANGULAR 3 /* spherical, longitude along x, polar angle down y */

/* A pixel (px, py), row 0 at the top, is screen point (sx, sy) = (2 (px + 0.5) / width - 1 +
 * center[0], 1 - 2 (py + 0.5) / height + center[1]); a perspective camera looks along
 * forward + sx * right + sy * up, an orthographic one along forward from position + sx * right +
 * sy * up. A spherical camera maps the image on the sphere of directions in the frame (right, up,
 * forward), all three unit. */
typedef struct {
  float position[3];
  int width;
  float forward[3];
  int height;
  float right[3]; /* perspective: scaled by tan(fov/2) and the screen window; orthographic: in world units */
  float lens_radius; /* perspective: 0 for a pinhole */
  float up[3];       /* scaled as right */
  float focal_distance;
  int filter;             /* the pixel filter, KASHA_FILTER_* (geometry/pixel_filter.h) */
  float filter_radius[2]; /* in pixels, per axis */
  int type;               /* KASHA_CAMERA_* */
  float filter_cdf[2][KASHA_FILTER_BINS]; /* KASHA_FILTER_TABLE: per axis, the filter's mass on
                                             the half axis up to each bin's end (the last 1) */
  float center[2]; /* the screen window's centre, in units of right and up */
  float pad[2];
} KCamera;
KASHA_STATIC_SIZE(KCamera, 224);

/* The scene as kernels take it by value, first of KASHA_SCENE_PARAMS (kernels/geometry/scene_view.h): the
 * camera, the light counts and the bin width, and where each of the scene's tables starts in its
 * one read-only buffer (byte offsets, multiples of 256, set by DeviceScene): one argument for what
 * were 19, since an OpenCL 1.2 kernel cannot take a struct holding pointers. */
typedef struct {
  KCamera camera;
  ulong nodes, leaves, tris, materials, spectra, lobes, emitter_radiance, emitter_area_pdf, light_tri,
      light_cdf, lights, textures, texcoords, normals, light_nodes, light_trails, instances,
      tangents, light_spheres, tex_ops, media, tri_media; /* see SceneView */
  int light_count;     /* entries of light_tri and light_cdf */
  float bin_nm;
  int light_sources;   /* entries of lights */
  int light_triangles; /* the emitting triangles: the first entries of light_tri */
  int camera_medium;   /* the medium the camera is in (KMedium index), -1: vacuum */
  float scene_radius;  /* the triangles' bounding sphere (Scene::bounding_sphere): no medium */
  float scene_center[3]; /* scatters beyond it (transport/medium_flight.h) */
  int pad_params;
} KSceneParams;
KASHA_STATIC_SIZE(KSceneParams, 440);

/* A dye in a medium (docs/media.md#fluorescent-media): offsets in the spectra buffer of its
 * absorption a per bin (per scene unit of length) and of ê (sums to 1), its quantum yield Φ and
 * Σ_i a_i (the branch choice's energy under equal-energy light). */
typedef struct {
  int absorption;
  int emission;
  float yield;
  float absorption_sum;
} KFluorophore;
KASHA_STATIC_SIZE(KFluorophore, 16);

#define KASHA_MEDIUM_FLUOROPHORES 4 /* host/scene/medium.h's kMaxMediumFluorophores */

/* A participating medium (kernels/media/medium.h, docs/media.md): offsets in the spectra buffer
 * of its extinction σt = σa + σs + Σ a_f and scattering σs per bin (per scene unit of length, times
 * the density of its grid where it has one), its Henyey–Greenstein g, and its fluorophores. Uploaded only for scenes with media
 * (KASHA_MEDIA). */
typedef struct {
  int sigma_t;
  int sigma_s;
  float g;
  int fluorophores; /* how many of fluorophore[] it holds */
  KFluorophore fluorophore[KASHA_MEDIUM_FLUOROPHORES];
  /* What vcm's MIS weights take of it, functions of the medium alone so that both subpaths
   * find them alike (kernels/vcm/vcm_media.h): σt's mean over the bins, the elastic share of
   * its events Σσs / (Σσs + Σ_f Φ_f Σa_f), and that sum (0: a collision only absorbs). */
  float sigma_mean;
  float elastic_share;
  float events;
  /* A grid's density (kernels/media/density_grid.h): its samples in the spectra buffer (-1: a
   * homogeneous medium), how many along x, y, z, and the affine map (row-major 3 × 4) from the
   * world to its lattice, where sample (i, j, k) sits at (i, j, k). */
  int density;
  int grid_size[3];
  /* Its emission σa·Le per bin in the spectra buffer (times the grid's density), -1: none. */
  int emission;
  float to_grid[12];
  /* A grid's emission beyond a spectrum (kernels/media/medium_emission.h), on the density's
   * samples in the spectra buffer, -1: none: a scale per sample, and a temperature per sample
   * whose blackbody (peak 1) takes Le's place where T = (v − temperature_offset) ·
   * temperature_scale > 100 K, averaged over each bin at its two Gauss nodes (bin_nodes: 2 per
   * bin, in nm). */
  int emission_scale;
  int temperature;
  int bin_nodes;
  float temperature_offset;
  float temperature_scale;
  /* A component grid (kernels/media/colour_grid.h), σa and σs varying in colour over its grid:
   * its components (0: not one), each a grid of weights (the k-th after `density`) with σt and σs
   * spectra (the k-th after sigma_t and sigma_s); the first slot of the trail its components
   * after the first take (the first takes the medium's own); whether the last component is 1
   * everywhere in the box (pbrt-v4's rgbgrid without a σa or σs grid) and has no samples. */
  int components;
  int trail_extra;
  int uniform_last;
  /* Light paths that start in it where it emits (kernels/transport/medium_light.h): the
   * probability that a light path does (0: none), the box they start in as a map from the unit
   * cube (row-major 3 × 4) and its volume, and whether it is the medium outside every boundary. */
  float light_pick;
  float light_box[12];
  float light_volume;
  int light_outer;
  /* An emitting component grid's radiance (kernels/media/medium_emission.h), pbrt-v4's rgbgrid
   * "Le": its components (0: none), each a grid of weights (the j-th after emission_scale) with a
   * radiance per bin (the j-th after emission); it emits σa(x) Σ_j ρ_j(x) Le_j. */
  int emission_components;
} KMedium;
KASHA_STATIC_SIZE(KMedium, 256);

/* Per leaf triangle (KASHA_MEDIA), its shape's media: inside (behind the front side) and outside,
 * KMedium indices, -1 for vacuum. Equal sides are no boundary: a ray keeps its medium there. */
typedef struct {
  int inside;
  int outside;
} KTriMedia;
KASHA_STATIC_SIZE(KTriMedia, 8);

/* What a material is: the measured model (gloss lobe or mirror, passive and fluorescent Lambert
 * parts), or an ideal specular interface — a dielectric or a conductor (docs/materials.md). */
#define KASHA_KIND_MEASURED 0
#define KASHA_KIND_DIELECTRIC 1
#define KASHA_KIND_CONDUCTOR 2
#define KASHA_KIND_MIX 3 /* one of two other materials per point (materials/mix.h) */
#define KASHA_KIND_INTERFACE 4 /* no surface: only a boundary between media (media/medium.h) */
#define KASHA_MIX_DEPTH 8 /* mixes nest at most this deep (host/material/mix.h's kMaxMixDepth) */

/* A mix's two materials (indices into the material table) and the second's share at a point: the
 * constant amount, or a scalar KTexture's value there. */
typedef struct {
  int materials[2];
  float amount;
  int amount_texture; /* -1: the constant */
} KMix;
KASHA_STATIC_SIZE(KMix, 16);

/* Per-material data the kernels read; spectra live in one float buffer at the given offsets
 * (N values each, -1 when the part is absent; the buffer starts with N zeros that kernels read
 * in place of an absent part). */
typedef struct {
  int passive;    /* rho(lambda) */
  int excitation; /* a(lambda) */
  int emission;   /* e_hat = e * bin width, sums to 1 */
  int lobe;       /* gloss lobe table (KASHA_LOBE_CELLS pdf values then as many CDF values), -1: mirror */
  float gloss;    /* g; 0 without a gloss part */
  float cone_rad; /* half-angle of the gloss cone */
  float excitation_sum; /* sum_i a_i, for the branch probabilities */
  int kind;             /* KASHA_KIND_* */
  float albedo_xyz[3]; /* colour under equal-energy light, fluorescence included (debug view) */
  float eta;           /* dielectric: index inside (behind the front side) over outside */
  int eta_spectrum;    /* conductor: eta(lambda) and k(lambda), the complex index over the outside's;
                        * a dispersive dielectric: eta(lambda) (-1: eta holds for every bin) */
  int k_spectrum;
  float alpha[2]; /* a dielectric's or conductor's GGX roughness (alpha_x, alpha_y); 0: smooth */
  int reflectance_texture;  /* KTexture multiplying the passive reflectance, -1: none */
  int fluorescence_texture; /* KTexture scaling the excitation (an ink's concentration), -1: none */
  float coat_eta;       /* a smooth dielectric coat over the Lambert parts (kernels/materials/coat.h): its
                         * index; 0: no coat */
  float coat_thickness; /* its optical depth along the normal */
  float coat_internal;  /* R̄: of the base's light, the share the coat sends back down */
  float coat_albedo;    /* τ̄ / η²: the diffuse part's albedo per unit of outgoing transmission */
  float coat_alpha;     /* a rough coat's GGX roughness; 0: smooth */
  int coat_table;       /* a rough coat's E(μ) then t(μ), KASHA_COAT_TABLE values each at
                         * μ = k / (KASHA_COAT_TABLE − 1) (a layered metal's Lambert part: its own
                         * t(μ), host/material/layered_metal.h); -1: a smooth coat's formulas */
  int transmittance;    /* tau(lambda): Lambert transmission to the other side; -1: none */
  float transmit_share; /* the share of Lambert samples sent through (surface.h); 0 without tau */
  int thin;             /* a dielectric: 1 for a thin sheet (fresnel.h's thin_dielectric_reflectance) */
  int normal_map;       /* KTexture of its normal map (materials/normal_map.h), -1: none */
  int alpha_texture[2]; /* scalar KTextures whose values are alpha[0], alpha[1]'s roughness at a point
                         * (materials/texture.h), -1: the constant alpha */
  int remap_alpha;      /* 1: a texture's roughness r gives alpha sqrt(r) (pbrt-v4's RoughnessToAlpha) */
  int under_coat;       /* a conductor: 1 for the metal seen through its rough layer's coat, one
                         * scattering (materials/metal_under_coat.h); 0: bare or both smooth */
  KMix mix;             /* KASHA_KIND_MIX: what it mixes */
  float layer_scale;    /* a rough layered metal's part (host/material/layered_metal.h): its
                         * reflectance over the share of points it is chosen at; else 1 */
  float pad_material[3];
} KMaterial;
KASHA_STATIC_SIZE(KMaterial, 160);

/* Entries of a rough coat's tables (host/material/coat.h's kCoatTableSize). */
#define KASHA_COAT_TABLE 64

/* A texture as the kernels look it up (docs/textures.md) at a hit's (u, v): an image of texels,
 * or a checkerboard of two values. Spectral content (a reflectance) is per bin: an image's texel
 * holds the RGB sigmoid's coefficients (c0, c1, c2, 0; the spectrum S(c0 λ² + c1 λ + c2)), a
 * checkerboard two spectra; scalar content (a concentration) is one float per texel, or two
 * numbers. */
#define KASHA_TEXTURE_IMAGE 0
#define KASHA_TEXTURE_CHECKERBOARD 1
#define KASHA_TEXTURE_PROGRAM 2 /* a texture of textures (shared/texture_program.h) */
#define KASHA_WRAP_REPEAT 0
#define KASHA_WRAP_CLAMP 1
#define KASHA_WRAP_BLACK 2
#define KASHA_WRAP_OCTAHEDRAL 3 /* pbrt-v4's octahedralsphere: mirrored across the edges */

typedef struct {
  int type;          /* KASHA_TEXTURE_* */
  int data;          /* image: offset of its texels in the spectra buffer (4 floats each if
                      * spectral, 1 if scalar, 3 for a normal map), row 0 at the top */
  int width, height; /* image */
  int wrap;          /* KASHA_WRAP_* */
  int bilinear;      /* image: 1 bilinear, 0 nearest */
  int lambda;        /* spectral image: offset of the bins' centre wavelengths */
  int spectral;      /* 1: spectral content, 0: scalar */
  float uscale, vscale, udelta, vdelta; /* (s, t) = (u·uscale + udelta, v·vscale + vdelta) */
  int even, odd;     /* spectral checkerboard: offsets of its two spectra */
  float even_value, odd_value; /* scalar checkerboard */
  int first_op, ops;     /* program: its scalar steps, KTexOps [first_op, first_op + ops) */
  int first_term, terms; /* spectral program: its terms, KTexOps [first_term, first_term + terms) */
} KTexture;
KASHA_STATIC_SIZE(KTexture, 80);

/* One step of a texture program (docs/textures.md#textures-of-textures): pbrt-v4's textures of
 * textures (mix, scale, checkerboard of textures, dots, bilerp, the noise textures, mappings other
 * than (u, v)) compiled by the host into steps over a few private slots, so the kernels evaluate a
 * tree without recursion. A scalar step writes slot dst (a mapping writes dst, dst + 1 and, in
 * 3D, dst + 2) from the slots a, b, c it reads. A spectral program ends in terms: each adds slot
 * a's value times a spectrum (a constant one, or an image's texel blend at slots b, c). */
#define KASHA_TEXOP_CONST 0     /* f[0] */
#define KASHA_TEXOP_MAP_UV 1    /* (u·f0 + f2, v·f1 + f3) */
#define KASHA_TEXOP_MAP_SPHERE 2 /* pbrt-v4's spherical mapping of the point by the matrix at ref */
#define KASHA_TEXOP_MAP_CYLINDER 3
#define KASHA_TEXOP_MAP_PLANE 4  /* (f6 + p·(f0 f1 f2), f7 + p·(f3 f4 f5)), p by the matrix */
#define KASHA_TEXOP_MAP_3D 5     /* the point by the matrix at ref: three slots */
#define KASHA_TEXOP_IMAGE 6      /* scalar image KTexture ref at (a, b) */
#define KASHA_TEXOP_CHECKER_2D 7 /* 1 on the odd squares at (a, b), 0 on the even */
#define KASHA_TEXOP_CHECKER_3D 8 /* 1 on the odd cubes at (a, a + 1, a + 2) */
#define KASHA_TEXOP_DOTS 9       /* 1 inside pbrt-v4's polka dots at (a, b), 0 outside */
#define KASHA_TEXOP_BILERP 10    /* f0..f3 = v00, v01, v10, v11 at (a, b) */
#define KASHA_TEXOP_FBM 11       /* at (a, a + 1, a + 2): octaves, f0 = roughness (ω) */
#define KASHA_TEXOP_WRINKLED 12  /* pbrt-v4's Turbulence, as FBM */
#define KASHA_TEXOP_WINDY 13
#define KASHA_TEXOP_MARBLE 14    /* the marble's spline parameter in [0, 1]: octaves, f0 ω, f1 scale,
                                  * f2 variation */
#define KASHA_TEXOP_DIRECTION 15 /* |n · (f0 f1 f2)| */
#define KASHA_TEXOP_MUL 16       /* a · b */
#define KASHA_TEXOP_LERP 17      /* (1 − a)·b + a·c */
#define KASHA_TEXOP_ONE_MINUS 18 /* 1 − a */
#define KASHA_TEXOP_TERM_SPECTRUM 19 /* term: slot a times the spectrum at offset ref */
#define KASHA_TEXOP_TERM_IMAGE 20    /* term: slot a times spectral image KTexture ref at (b, c) */
#define KASHA_TEXTURE_SLOTS 32 /* the most slots a program uses (the host refuses more) */
typedef struct {
  int type; /* KASHA_TEXOP_* */
  int dst;
  int a, b, c;
  int ref;     /* a KTexture, a spectrum's offset, or a 3×4 matrix's (texture from world) */
  int octaves; /* the noise steps' */
  int pad_op;
  float f[8];
} KTexOp;
KASHA_STATIC_SIZE(KTexOp, 64);

/* A triangle's texture coordinates, in leaf order like KTriangle: (u, v) at v0, v1, v2; the
 * texture its emission is multiplied by and the scalar texture of its shape's alpha cut-out
 * (shared/alpha_test.h; -1: none). */
typedef struct {
  float uv[6];
  int emission_texture;
  int alpha_texture;
} KTexcoords;
KASHA_STATIC_SIZE(KTexcoords, 32);

/* A triangle's shading normals at v0, v1, v2 (OBJ `vn`), in leaf order like KTriangle; uploaded
 * only when some shape has them (docs/formats.md#shading-normals). */
typedef struct {
  float n[9];
  float pad[3];
} KShadingNormals;
KASHA_STATIC_SIZE(KShadingNormals, 48);

/* Lights that are not emitting triangles (docs/lights.md): a point, a spot (a point whose
 * intensity falls off to zero at the edge of a cone), a distant light (parallel light of a given
 * irradiance) and an infinite light (radiance from every direction, constant or an environment
 * image). Light sampling picks them from the same CDF as the emitting triangles, in proportion to
 * their power (next-event estimation then picks within the triangles' share by the light BVH,
 * KLightNode): their entries of light_tri are ~index into the KLight array. */
#define KASHA_LIGHT_POINT 0
#define KASHA_LIGHT_SPOT 1
#define KASHA_LIGHT_DISTANT 2
#define KASHA_LIGHT_INFINITE 3

typedef struct {
  int type;         /* KASHA_LIGHT_* */
  int spectrum;     /* row of emitter_radiance: intensity (point, spot; W sr⁻¹ nm⁻¹), irradiance
                     * (distant; W m⁻² nm⁻¹), radiance (infinite; W m⁻² sr⁻¹ nm⁻¹) */
  float pick;       /* the probability that light sampling picks it */
  int image;        /* infinite: offset of its image in the spectra buffer (4 floats a texel: the
                     * sigmoid's c0, c1, c2 and a scale, kernels/lights/environment.h), -1: constant */
  float position[3]; /* point, spot; distant and infinite: the centre of the scene's bounding sphere */
  float radius;      /* distant, infinite: the radius of the scene's bounding sphere */
  float axis[3];     /* spot: the cone's axis; distant: the direction the light travels */
  float cos_total;   /* spot: the cone's edge, where the intensity reaches 0 */
  float cos_falloff; /* spot: where the falloff begins (full intensity inside) */
  int width, height; /* infinite: the image's size (its pixels) */
  int mapping;       /* infinite: KASHA_MAPPING_* */
  float to_light[9]; /* infinite: the linear map from world directions to the image's frame, row
                      * by row (directions are normalised after it) */
  int distribution;  /* infinite: offset of the image's sampling distribution, -1: uniform sphere */
  int lambda;        /* infinite with an image: offset of the bins' centre wavelengths (nm) */
  int general;       /* infinite: to_light is not orthogonal (its inverse and Jacobian are used) */
  int medium;        /* point, spot: the medium it is in (KMedium index), -1: vacuum */
  float pad[3];
} KLight;
KASHA_STATIC_SIZE(KLight, 128);

/* A node of the light BVH that next-event estimation picks an emitting triangle with
 * (kernels/lights/light_bvh.h): pbrt-v4's LightBVHNode, its LightBounds kept in floats. The box
 * of its triangles, the cone of their front normals (axis w, cosine of its half-angle cos_o) and
 * their power phi (W); every emitter is a one-sided triangle, so pbrt-v4's θe is π/2 throughout.
 * child >= 0: an interior node, its first child the next node and its second node `child`;
 * < 0: a leaf, the emitting triangle ~child (leaf order, as KTriangle). Node 0 is the root. */
typedef struct {
  float lo[3];
  float phi;
  float hi[3];
  float cos_o;
  float w[3];
  int child;
} KLightNode;
KASHA_STATIC_SIZE(KLightNode, 48);

/* Per emitting triangle (as light_tri lists them), under KASHA_SPHERE_LIGHTS: the sphere it
 * tessellates, which next-event estimation samples as one light by the solid angle it subtends
 * (kernels/lights/sphere_light.h): its centre and the radius of a sphere holding all its vertices;
 * radius 0 for a triangle of no such sphere. */
typedef struct {
  float centre[3];
  float radius;
} KSphereLight;
KASHA_STATIC_SIZE(KSphereLight, 16);

/* A path from the light BVH's root to a leaf: bit k chooses the second child at depth k, so the
 * deepest tree the builder may make (host/render/light_bvh.cpp) has 64 levels below the root. */
#define KASHA_LIGHT_BVH_MAX_DEPTH 64

/* How an environment image covers the sphere of directions. */
#define KASHA_MAPPING_LATLONG 0
#define KASHA_MAPPING_EQUAL_AREA 1

/* Gloss lobes are tabulated in this many equal rings of angle from the mirror direction. */
#define KASHA_LOBE_CELLS 64

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
