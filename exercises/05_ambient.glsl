// Exercise, chapter 05: ambient light (thesis 3.1).
// replaces: common/shading.glsl#ambient
// The light that arrives from everywhere at once, the same at every point:
// I_g = k_a I_a, the material's ambient colour (m.ka.rgb) times the
// scene's ambient light (camera.ambient.rgb). Until it is written, every
// object is black against the sky.
vec3 ambientTerm(GpuMaterial m) {
    // TODO(you): I_g = k_a I_a
    return vec3(0.0);
}
