// Strata multi-volume ray caster: volume @n@'s point components at a point of the local frame,
// from one 3-D texture of the whole volume with a channel per component (never the atlas, whose
// bricks hold one scalar), point (i, j, k) at index coordinates (i, j, k); each component
// interpolated on its own, snapped to the nearest voxel for nearest-point interpolation.
uniform sampler3D uVolume@n@;
uniform vec3 uDims@n@;
uniform mat4 uLocalToIndex@n@;
uniform float uNearest@n@; // 1: nearest-point interpolation
vec4 strataComponents@n@(vec3 p)
{
  vec3 idx = (uLocalToIndex@n@ * vec4(p, 1.0)).xyz;
  idx = mix(idx, floor(idx + 0.5), uNearest@n@);
  return textureLod(uVolume@n@, (idx + 0.5) / uDims@n@, 0.0);
}
