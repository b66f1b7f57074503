// Chapter 14: the photon pass. One invocation per photon: it leaves a
// light toward a glass or a mirror (the emitters, shared/photons/
// photon_map.cpp's photonEmitters), follows reflection and refraction as chapter 13's ray
// tree does, but one branch at a time, chosen at random with the Fresnel
// shares as probabilities (Russian roulette: the photon's power never
// grows but where chapter 15's compensated shares exceed 1, and on average
// each branch gets its share), is absorbed along the
// way, and is stored where it meets a diffuse surface after at least one
// mirror or glass: the caustic photon map.
#ifndef PHOTON_TRACE_GLSL
#define PHOTON_TRACE_GLSL
#include "rt_bindings.glsl"
#include "payload.glsl"
#include "camera.glsl"
#include "shading.glsl"
#include "raygen_common.glsl"
#include "radiometry.glsl"  // chapter 15: the rough glints' shadow rays
#include "ray_tree.glsl"
#include "spectrum.glsl"
#include "photon_map.glsl"

// reflections and refractions a photon follows at most
#define PHOTON_BOUNCES 16u

uint rng;
float random() {
    rng = pcgHash(rng);
    return toUnit(rng);
}


// [region emit]
// Emitter e's cone, from a point light: its axis and the cosine of its
// half-angle (-1: the light is inside the sphere, every direction).
float coneCosine(PhotonEmitter e, vec3 light, out vec3 axis) {
    vec3 toCentre = e.target.xyz - light;
    float d = length(toCentre);
    axis = toCentre / d;
    float sine = e.target.w / d;
    return sine < 1.0 ? sqrt(1.0 - sine * sine) : -1.0;
}

// A photon's start, direction and power (watts). The emitter is chosen by
// its share; the power is the light's over the probability density of
// what was drawn, summed over every emitter of that light that could have
// drawn it (one-sample multiple importance sampling, balance heuristic),
// so cones and beams that overlap count their light once.
void emitPhoton(out vec3 origin, out vec3 direction, out vec3 power) {
    PhotonMapRef map = PhotonMapRef(push.photonMap);
    EmittersRef emitters = EmittersRef(map.header.emitters);
    uint count = map.header.emitterCount;
    float u = random();
    uint k = 0u;
    while (k + 1u < count && emitters.emitters[k].cumulative < u) ++k;
    PhotonEmitter e = emitters.emitters[k];
    GpuLight light = lights[e.light];
    vec2 v = vec2(random(), random());
    float density = 0.0;  // per steradian (a point light) or square metre (a sun)
    if (light.position.w == LIGHT_DIRECTIONAL) {
        // a point of the beam's disc, uniformly; the photon starts before it
        direction = light.position.xyz;
        mat3 frame = basisAround(direction);  // sampling.glsl
        vec3 t = frame[0], b = frame[1];
        // a sun with a disc tilts each photon by up to its angular radius:
        // the beam widens by as much across the target's depth
        float grow = kSunDiscs ? 1.0 + tan(light.intensity.w) : 1.0;
        float radius = e.target.w * grow * sqrt(v.x), phi = 2.0 * kPi * v.y;
        vec3 x = e.target.xyz + radius * (cos(phi) * t + sin(phi) * b);
        for (uint j = 0u; j < count; ++j) {
            PhotonEmitter o = emitters.emitters[j];
            if (o.light != e.light) continue;
            vec3 off = x - o.target.xyz;
            off -= direction * dot(off, direction);  // across the beam
            float r = o.target.w * grow;
            // the emitter drawn from always counts: rounding may put a point
            // drawn on its rim outside it (density 0, a photon of infinite power)
            if (j == k || dot(off, off) < r * r)
                density += o.probability / (kPi * r * r);
        }
        if (kSunDiscs && light.intensity.w > 0.0)  // through x from a point of the disc
            direction = -towardSun(light, vec2(random(), random()));
        origin = x - direction * e.backoff;
    } else {
        // a direction of the cone, uniformly over its solid angle
        vec3 axis;
        float cosMax = coneCosine(e, light.position.xyz, axis);
        float cosine = 1.0 - v.x * (1.0 - cosMax);
        float sine = sqrt(max(0.0, 1.0 - cosine * cosine)), phi = 2.0 * kPi * v.y;
        mat3 frame = basisAround(axis);
        direction =
            normalize(cosine * axis + sine * (cos(phi) * frame[0] + sin(phi) * frame[1]));
        for (uint j = 0u; j < count; ++j) {
            PhotonEmitter o = emitters.emitters[j];
            if (o.light != e.light) continue;
            vec3 oAxis;
            float oCos = coneCosine(o, light.position.xyz, oAxis);
            if (j == k || dot(direction, oAxis) >= oCos)  // the drawn one always
                density += o.probability / (2.0 * kPi * (1.0 - oCos));
        }
        origin = light.position.xyz;
    }
    power = light.intensity.rgb / (float(push.photonsEmitted) * density);
}
// [end]

void storePhoton(vec3 p, vec3 n, vec3 power) {
    PhotonMapRef map = PhotonMapRef(push.photonMap);
    uint i = atomicAdd(map.header.stored, 1u);
    if (i < map.header.capacity)
        PhotonsRef(map.header.photons).photons[i] =
            Photon(p, packSnorm4x8(vec4(n, 0.0)), power, 0u);
}

void main() {
    // --photon-seed picks a stream of photon sets: the frame counter XOR a
    // pattern from the seed's hash (0 for seed 0; pcgHash is a bijection, so
    // distinct seeds give distinct patterns). Two seeds' runs of F frames
    // share a set with a chance of about F^2 / 2^32; adding the seed to the
    // frame, as before, made seed N reuse all but N of seed 0's sets.
    uint stream = pcgHash(push.photonSeed) ^ pcgHash(0u);
    rng = pcgHash(gl_LaunchIDEXT.x ^ pcgHash((push.frame + 0x9E3779B9u) ^ stream));
    vec3 origin, direction, power;
    emitPhoton(origin, direction, power);
    uint media = 0u;  // lights are in air
    float tMax = kInfinity;
    bool specular = false;  // met a mirror or glass: stored at the next diffuse hit
    // chapter 13's dispersion: the wavelength it carries from its first
    // dispersive surface on (--wavelength: that one, unweighted)
    bool oneWavelength = push.wavelength >= SPECTRUM_MIN_NM, spectral = false;
    float nm = oneWavelength ? push.wavelength
                             : mix(SPECTRUM_MIN_NM, SPECTRUM_MAX_NM, random());
    uint passes = 0u;
    for (uint bounce = 0u; bounce <= PHOTON_BOUNCES;) {
        traceClosest(origin, 0.0, direction, tMax, 0.0);
        if (payload.t < 0.0) {  // escaped
            atomicAdd(PhotonMapRef(push.photonMap).header.escaped, 1u);
            return;
        }
        power *= transmittance(media, payload.t);  // Beer-Lambert
        // [region photon_hit]
        // The surface as the camera rays' tree sees it (ray_tree.glsl's growBranch).
        GpuMaterial m = hitMaterial();
        vec3 n = facingNormal(payload.normal, direction);
        vec3 ns = hitFacingShading(direction);
        vec3 p = payload.position;
        float e = payload.error, radius = objects[payload.object].radius;
        bool entering = payload.frontFace == 1u;
        float n1 = entering ? 1.0 : m.params.w, n2 = entering ? m.params.w : 1.0;
        uint beyond = media;
        bool thin = kThinWalls && (m.flags & MATERIAL_THIN) != 0u;
        if (thin) n1 = mediumIor(currentMedium(media)), n2 = m.params.w;
        if (m.params.z > 0.0 && !thin) {
            Boundary boundary =
                boundaryAt(media, objects[payload.object].material, entering);
            if (!boundary.real) {  // no surface: on into the new media
                origin = secondaryOrigin(p, e, -n);
                tMax = entering ? insideReach(origin, p, radius) : kInfinity;
                media = boundary.beyond;
                // still glass to the shadow rays, which stop at it: the light
                // beyond (an index-1 ball's whole shadow) is the photons'
                specular = true;
                if (++passes > MAX_PASSES) break;
                continue;
            }
            n1 = boundary.n1, n2 = boundary.n2, beyond = boundary.beyond;
            if (mediumDispersion(boundary.from) != vec2(0.0) ||
                mediumDispersion(boundary.to) != vec2(0.0)) {
                n1 = mediumIorAt(boundary.from, nm);
                n2 = mediumIorAt(boundary.to, nm);
                if (!spectral && !oneWavelength) power *= spectralWeight(nm);
                spectral = true;
            }
        }
        Split s = splitBetween(m, n1, n2, ns, direction);
        // [end]
#ifdef MICROFACET
        // chapter 15: a rough surface's shares and directions, about one
        // visible normal of the photon's own (rough_surface.glsl)
        float alpha = roughAlpha(m);
        RoughSplit rough;
        if (alpha > 0.0) {
            rough = roughSplit(m, alpha, n1, n2, n, ns, direction,
                               vec2(random(), random()));
            s.reflected = rough.reflectedShare, s.refracted = rough.refractedShare;
            // compensated shares may add up past 1: the roulette then
            // chooses by their ratio and the photon carries their sum
            float sum = s.reflected + s.refracted;
            if (sum > 1.0) power *= sum, s.reflected /= sum, s.refracted /= sum;
        }
#endif
        // [region store]
        // A diffuse surface after a mirror or glass: a caustic photon. Its
        // whole power is stored (the irradiance arriving); the surface's
        // share `local` is applied when the camera's rays gather it.
        if (specular && s.local > 0.0 && maxComponent(m.kd.rgb) > 0.0)
            storePhoton(p, n, power);
        if (bounce == PHOTON_BOUNCES) break;
        // Russian roulette on the shares: refracted, reflected, or neither
        // (absorbed, or scattered diffusely: the surface's own light, which
        // shadow rays and the next bounce of a camera ray account for).
        float u = random();
        if (u < s.refracted) {
            vec3 t = thin ? direction : refractedDirection(direction, n, ns, s.eta);
#ifdef MICROFACET
            if (alpha > 0.0) t = rough.refracted;
#endif
            if (t != vec3(0.0)) {
                origin = secondaryOrigin(p, e, -n);
                tMax = entering && !thin ? insideReach(origin, p, radius) : kInfinity;
                media = beyond;
                direction = t;
            } else {  // only a mesh's flat triangle can reflect it all
                u = s.refracted;  // reflected below
            }
        }
        if (u >= s.refracted) {
            if (u >= s.refracted + s.reflected) return;
            origin = secondaryOrigin(p, e, n);
            tMax = entering || thin ? kInfinity : insideReach(origin, p, radius);
            direction = reflectedDirection(direction, n, ns);
#ifdef MICROFACET
            if (alpha > 0.0) direction = rough.reflected;
#endif
        }
        // [end]
        specular = true;
        ++bounce;
    }
    atomicAdd(PhotonMapRef(push.photonMap).header.lost, 1u);  // a limit stopped it
}
#endif
