x0 = (uLocalToIndex@n@ * vec4(o + t * d, 1.0)).xyz;
  dx = dir * (mat3(uLocalToIndex@n@) * d);
  c = clamp(ivec3(floor(x0 / uSkipGrid@n@.w)), ivec3(0), ivec3(uSkipGrid@n@.xyz) - 1);
  D = float(texelFetch(uSkip@n@, c, 0).r);
  if (D == 0.0)
  {
    return t;
  }
  lo = (vec3(c) - (D - 1.0)) * uSkipGrid@n@.w;
  hi = (vec3(c) + D) * uSkipGrid@n@.w;
  te = vec3(dx.x > 0.0 ? (hi.x - x0.x) / dx.x : (dx.x < 0.0 ? (lo.x - x0.x) / dx.x : 3.0e38),
    dx.y > 0.0 ? (hi.y - x0.y) / dx.y : (dx.y < 0.0 ? (lo.y - x0.y) / dx.y : 3.0e38),
    dx.z > 0.0 ? (hi.z - x0.z) / dx.z : (dx.z < 0.0 ? (lo.z - x0.z) / dx.z : 3.0e38));
  until = min(until, max(min(te.x, min(te.y, te.z)), 0.0));
