// Strata multi-volume ray caster: cropping of volume @n@, vtkVolumeMapper's 27 regions. The
// planes are in index coordinates; region (x, y, z), each 0 below an axis's first plane, 1
// between, 2 above, is shown when bit x + 3 y + 9 z of the flags is set. 1.0: shown.
uniform vec3 uCropLo@n@;
uniform vec3 uCropHi@n@;
uniform int uCropFlags@n@;
float strataCrop@n@(vec3 p)
{
  vec3 x = (uLocalToIndex@n@ * vec4(p, 1.0)).xyz;
  ivec3 r = ivec3(step(uCropLo@n@, x) + step(uCropHi@n@, x));
  return float((uCropFlags@n@ >> (r.x + 3 * r.y + 9 * r.z)) & 1);
}
