// Exercise, chapter 15: the microfacet normal a ray meets.
// replaces: common/microfacet.glsl#visible_normals
// Draw a normal m with the density of the normals wo sees,
// D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z (Heitz 2018). Dupuy and
// Benyoub's way (2023): stretch wo by alpha in x and y and normalize (the
// surface becomes alpha = 1, a hemisphere); take the point of the unit
// sphere with z = (1 - u.y) (1 + s.z) - s.z and angle 2 pi u.x around z
// (s: the stretched wo); add s; stretch x and y back by alpha; normalize.
// Until it is written every facet is flat: the frosted balls look clear.
vec3 sampleVisibleNormal(vec3 wo, float alpha, vec2 u) {
    // TODO(you): a visible normal for the sample point u
    return vec3(0.0f, 0.0f, 1.0f);
}
float visibleNormalPdf(vec3 wo, vec3 m, float alpha) {
    return smithG1(wo, alpha) * max(0.0f, dot(wo, m)) * ggxD(m, alpha) / wo.z;
}
