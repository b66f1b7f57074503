// Exercise, chapter 06: diffuse light (thesis 3.2).
// replaces: common/shading.glsl#diffuse
// For each of the camera.counts.z lights (lights[i].position.xyz,
// lights[i].intensity.rgb): the direction to it, l = safeNormalize(position
// - p). A light behind the surface (l . n <= 0) adds nothing and needs no
// ray; otherwise count a shadow ray (++rays) and ask lightVisible(origin,
// position) whether it lights p, and add I_i (l . n). Until it is written,
// only the ambient light shows.
vec3 diffuseTerm(GpuMaterial m, vec3 p, float error, vec3 n, inout uint rays) {
    vec3 sum = vec3(0.0);
    vec3 origin = secondaryOrigin(p, error, n);  // shadow rays start here
    // TODO(you): sum += I_i max(0, l . n) over the lights this point sees
    return m.kd.rgb * sum;
}
