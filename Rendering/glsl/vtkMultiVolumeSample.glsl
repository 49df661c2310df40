// Strata multi-volume ray caster: volume @n@'s scalar at a point of the local frame, through
// its local -> index matrix, snapped to the nearest voxel for nearest-point interpolation.
uniform mat4 uLocalToIndex@n@;
uniform float uNearest@n@; // 1: nearest-point interpolation
float strataScalar@n@(vec3 p)
{
  vec3 idx = (uLocalToIndex@n@ * vec4(p, 1.0)).xyz;
  return strataScalarAt@n@(mix(idx, floor(idx + 0.5), uNearest@n@));
}
