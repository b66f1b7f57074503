// Exercise, chapter 13: absorption (Beer-Lambert).
// replaces: common/media.glsl#beer_lambert
// Inside a medium light falls by exp(-sigma t) over a distance t, sigma
// the medium's absorption per unit length:
// mediumAbsorption(currentMedium(media)). A ray that leaves the scene (t <
// 0) inside an absorbing medium brings nothing back (1 where sigma is 0).
// Until it is written, coloured glass is clear.
vec3 transmittance(uint media, float t) {
    // TODO(you): exp(-sigma t)
    return vec3(1.0);
}
