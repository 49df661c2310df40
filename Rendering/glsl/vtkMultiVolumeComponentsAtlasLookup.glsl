// Strata multi-volume ray caster: volume @n@'s point components at a point of the local frame,
// from the brick atlas. Each component is a volume of one scalar there (its own bricks and
// index texture, co-registered with the others: strata::PagePoolFormat, Components), read by its
// own lookup (strataScalarAt@n@ for component 0, strataScalarAt@n@c<i> for component i) at the
// same index coordinates; snapped to the nearest voxel for nearest-point interpolation.
uniform mat4 uLocalToIndex@n@;
uniform float uNearest@n@; // 1: nearest-point interpolation
vec4 strataComponents@n@(vec3 p)
{
  vec3 idx = (uLocalToIndex@n@ * vec4(p, 1.0)).xyz;
  idx = mix(idx, floor(idx + 0.5), uNearest@n@);
  return vec4(//STRATA::ComponentFetches::Impl);
}
