// Exercise, chapter 11: rough surfaces (thesis 4.3).
// replaces: 11_rough/raygen.rgen#rough
// A rough surface's reflection is the mean over push.samplesPerHit rays
// spread round the mirror direction, as wide as the roughness:
// lobeDirection(mirror, roughness, samplePoint(push.pattern, first + i,
// count, seed)) gives ray i (seed: pixelSeed(gl_LaunchIDEXT.xy,
// push.frame)); a direction below the surface (d . n <= 0) is absorbed.
// Each ray's light is traceTree(from, d, 1u, vec3(s.reflected), rays,
// coneStart). Until it is written, rough surfaces are sharp mirrors.
// TODO(you): for roughness > 0, the mean over the lobe's rays
radiance += traceTree(from, mirror, 1u, vec3(s.reflected), rays, coneStart);
