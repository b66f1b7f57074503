// Exercise, chapter 07: the specular highlight (thesis 3.3, Blinn-Phong).
// replaces: common/shading.glsl#specular_power
// max(0, n . h)^shininess, h the half vector between the light and the eye
// (the caller has it): 0 where n . h <= 0, else pow(n . h, shininess).
// Until it is written, no surface shines.
float specularPower(vec3 n, vec3 h, float shininess) {
    // TODO(you): max(0, n . h)^shininess
    return 0.0;
}
