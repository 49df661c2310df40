//VTK::System::Dec
//STRATA::Extensions::Dec
// Strata stacked height-field ray caster (Lux & Froehlich, section 4): one pass, global
// min-max quadtree traversed top-down, per-leaf sorted depth intervals evaluated in ray order,
// linear search per layer with binary refinement. Tags are filled per scene by
// vtkStackedHeightFieldMapper: what the scene does not use leaves no code here.

// gl_FragData[i]: VTK declares fragOutput<i> and binds it to draw buffer i (two outputs without
// bound locations would be placed as the linker likes).
//VTK::Output::Dec

uniform mat4 uClipToGrid;  // NDC -> grid (homogeneous), composed in double on the CPU
uniform mat4 uGridToClip;
uniform vec4 uViewport;    // window x, y, width, height of the renderer
uniform vec2 uGridMax;     // nx - 1, ny - 1: the lateral box in cells
uniform vec2 uZRange;      // lowest and highest valid height of the stack
uniform float uZEps;       // slack of the height slabs, covers float rounding of the bilinear
uniform float uStep;       // linear-search step, in cells along the ground
uniform float uTieEps;     // ray-parameter tolerance under which two hits are a tie
uniform int uNumRegionPlanes;  // 6 with a region (SetRegion), else 0
uniform vec4 uRegionPlanes[6]; // its faces in grid space, inside: dot(n, g) + w <= 0
uniform int uTileSize;
uniform int uNumLevels;
uniform int uLevelOffset[16];
uniform ivec2 uLevelDims[16];
uniform samplerBuffer uNodes;      // min, max, interval offset, interval count
uniform samplerBuffer uIntervals;  // zmin, zmax, layer offset, layer count
uniform samplerBuffer uLayerLists; // layer ids

//STRATA::Holes::Dec

//STRATA::HeightLookup::Dec

//STRATA::Feedback::Dec

//STRATA::Color::Dec

//STRATA::Shading::Dec

//STRATA::Translucency::Dec

const float BIG = 3.0e38;

// f(t) = ray height - surface height, in the cell `c` whose corners are h (00, 10, 01, 11).
float strataF(vec3 o, vec3 d, float t, ivec2 c, vec4 h)
{
  vec3 p = o + t * d;
  vec2 uv = clamp(p.xy - vec2(c), 0.0, 1.0);
  float s = mix(mix(h.x, h.y, uv.x), mix(h.z, h.w, uv.x), uv.y);
  return p.z - s;
}

vec4 strataCorners(int layer, ivec2 c)
{
  return vec4(strataHeight(layer, c), strataHeight(layer, c + ivec2(1, 0)),
    strataHeight(layer, c + ivec2(0, 1)), strataHeight(layer, c + ivec2(1, 1)));
}

// The cells a layer's search walks inside one leaf: level-0 cells in core; under paging, the
// cells of the level the leaf's tile is resident at (one bilinear patch each, the same surface
// as its level-0 sub-cells interpolated, walked 2^l times faster).
//STRATA::CellCorners::Dec

// First crossing of `layer` for t in [ta, tb], in the cells [cLo, cHi] of one leaf: a walk over
// the cells the ray crosses, samples no further apart than uStep cells inside each, a sign change
// between consecutive samples (also across a cell boundary) refined by bisection and a final
// secant step. Cells are stepped as integers (no position is re-derived from t), so float
// rounding far from the grid origin cannot stall or skip the walk. Returns BIG when there is none.
float strataSearchLayer(int layer, vec3 o0, vec3 d0, float ta, float tb, ivec2 cLo0, ivec2 cHi0, out ivec2 hitCell)
{
  hitCell = ivec2(0);
  int lv = 0;
  //STRATA::SearchLevel::Impl
  // The ray in cells of level lv (t unchanged; exact: a power-of-two scale).
  float cellScale = float(1 << lv);
  vec3 o = vec3(o0.xy / cellScale, o0.z);
  vec3 d = vec3(d0.xy / cellScale, d0.z);
  ivec2 cLo = cLo0 >> lv;
  ivec2 cHi = cHi0 >> lv;
  ivec2 c = clamp(ivec2(floor((o + ta * d).xy)), cLo, cHi);
  ivec2 stepDir = ivec2(d.x > 0.0 ? 1 : -1, d.y > 0.0 ? 1 : -1);
  float lateral = length(d.xy);
  float t = ta;
  float tPrev = ta;
  float fPrev = 0.0;
  bool havePrev = false;
  for (int it = 0; it < 65536; ++it)
  {
    float tx = d.x > 0.0 ? (float(c.x + 1) - o.x) / d.x : (d.x < 0.0 ? (float(c.x) - o.x) / d.x : BIG);
    float ty = d.y > 0.0 ? (float(c.y + 1) - o.y) / d.y : (d.y < 0.0 ? (float(c.y) - o.y) / d.y : BIG);
    float tEnd = min(min(tx, ty), tb);
    vec4 h = strataCellCorners(layer, c);
    bool valid = true;
    //STRATA::Hole::Impl
    if (valid && tEnd >= t)
    {
      int n = max(1, int(ceil(lateral * (tEnd - t) / uStep)));
      float dt = (tEnd - t) / float(n);
      // The cell's first sample is the previous cell's last one when the walk is continuous.
      for (int k = havePrev && tPrev == t ? 1 : 0; k <= n; ++k)
      {
        float tc = (k == n) ? tEnd : t + float(k) * dt;
        float fc = strataF(o, d, tc, c, h);
        if (fc == 0.0)
        {
          hitCell = clamp(ivec2(floor((o0 + tc * d0).xy)), cLo0, cHi0);
          return tc;
        }
        if (havePrev && (fc > 0.0) != (fPrev > 0.0))
        {
          float a = tPrev, b = tc, fa = fPrev, fb = fc;
          for (int r = 0; r < 12; ++r)
          {
            float m = 0.5 * (a + b);
            float fm = strataF(o, d, m, c, h);
            if ((fm > 0.0) == (fa > 0.0) && fm != 0.0)
            {
              a = m;
              fa = fm;
            }
            else
            {
              b = m;
              fb = fm;
            }
          }
          float tHitLayer = fa != fb ? a + (b - a) * fa / (fa - fb) : b;
          hitCell = lv == 0 ? c : clamp(ivec2(floor((o0 + tHitLayer * d0).xy)), cLo0, cHi0);
          return tHitLayer;
        }
        tPrev = tc;
        fPrev = fc;
        havePrev = true;
      }
    }
    else
    {
      havePrev = false;
    }
    if (tEnd >= tb)
    {
      break;
    }
    if (tx < ty)
    {
      c.x += stepDir.x;
    }
    else
    {
      c.y += stepDir.y;
    }
    if (any(lessThan(c, cLo)) || any(greaterThan(c, cHi)))
    {
      break;
    }
    t = max(t, tEnd);
  }
  return BIG;
}

// The t range in which the ray's height lies in [z0, z1], intersected with [ta, tb].
vec2 strataSlab(vec3 o, vec3 d, float z0, float z1, float ta, float tb)
{
  if (d.z != 0.0)
  {
    float s0 = (z0 - uZEps - o.z) / d.z;
    float s1 = (z1 + uZEps - o.z) / d.z;
    return vec2(max(ta, min(s0, s1)), min(tb, max(s0, s1)));
  }
  bool inside = o.z >= z0 - uZEps && o.z <= z1 + uZEps;
  return inside ? vec2(ta, tb) : vec2(1.0, 0.0);
}

// The first hit of the stack for t in [tEnter, tExit]: top-down traversal. Nodes are stepped
// as integers across the face the ray leaves by and children are chosen by clamping into the
// parent, so that the walk always advances whatever the float rounding of positions far along
// the ray. False when there is none.
bool strataCast(vec3 o, vec3 d, float tEnter, float tExit, out float tHit, out int hitLayer, out ivec2 hitCell)
{
  // children are chosen by clamping into the parent, so that the walk always advances whatever
  // the float rounding of positions far along the ray.
  tHit = BIG;
  hitLayer = -1;
  hitCell = ivec2(0);
  float t = tEnter;
  int level = uNumLevels - 1;
  int S = uTileSize << level;
  ivec2 node = clamp(ivec2(floor((o + t * d).xy / float(S))), ivec2(0), uLevelDims[level] - 1);
  ivec2 stepDir = ivec2(d.x > 0.0 ? 1 : -1, d.y > 0.0 ? 1 : -1);
  bool up = d.z >= 0.0;
  for (int it = 0; it < 65536; ++it)
  {
    vec4 nd = texelFetch(uNodes, uLevelOffset[level] + node.y * uLevelDims[level].x + node.x);
    vec2 nlo = vec2(node * S);
    vec2 nhi = min(vec2((node + 1) * S), uGridMax);
    float tx = d.x > 0.0 ? (nhi.x - o.x) / d.x : (d.x < 0.0 ? (nlo.x - o.x) / d.x : BIG);
    float ty = d.y > 0.0 ? (nhi.y - o.y) / d.y : (d.y < 0.0 ? (nlo.y - o.y) / d.y : BIG);
    float tNodeExit = min(min(tx, ty), tExit);
    vec2 slab = nd.x <= nd.y ? strataSlab(o, d, nd.x, nd.y, t, tNodeExit) : vec2(1.0, 0.0);
    if (slab.x <= slab.y)
    {
      if (level > 0)
      {
        level -= 1;
        S >>= 1;
        t = max(t, slab.x);
        ivec2 child = ivec2(floor((o + t * d).xy / float(S)));
        node = clamp(child, node * 2, min(node * 2 + 1, uLevelDims[level] - 1));
        continue;
      }
      // Leaf: its depth intervals in ray order; the first one with a hit holds the nearest.
      int first = int(nd.z);
      int count = int(nd.w);
      ivec2 cLo = node * S;
      ivec2 cHi = min((node + 1) * S, ivec2(uGridMax)) - 1;
      for (int q = 0; q < count && hitLayer < 0; ++q)
      {
        vec4 iv = texelFetch(uIntervals, first + (up ? q : count - 1 - q));
        vec2 s = strataSlab(o, d, iv.x, iv.y, slab.x, slab.y);
        if (s.x > s.y)
        {
          continue;
        }
        float best = BIG;
        for (int r = 0; r < int(iv.w); ++r)
        {
          int layer = int(texelFetch(uLayerLists, int(iv.z) + r).x);
          //STRATA::Translucency::Skip
          ivec2 cell = ivec2(0);
          float th = strataSearchLayer(layer, o, d, s.x, min(s.y, best), cLo, cHi, cell);
          // Coincident horizons: a later one wins only when clearly nearer, so that float
          // noise cannot flip ids where two horizons are equal (the lower index wins ties).
          if (th < best - uTieEps)
          {
            best = th;
            hitLayer = layer;
            hitCell = cell;
          }
        }
        tHit = best;
      }
      if (hitLayer >= 0)
      {
        break;
      }
    }
    // On to the neighbour across the exit face, climbing while it lies in another parent.
    if (tNodeExit >= tExit)
    {
      break;
    }
    t = max(t, tNodeExit);
    ivec2 next = tx < ty ? ivec2(node.x + stepDir.x, node.y) : ivec2(node.x, node.y + stepDir.y);
    while (level < uNumLevels - 1 && any(notEqual(next >> 1, node >> 1)))
    {
      level += 1;
      S <<= 1;
      node >>= 1;
      next >>= 1;
    }
    if (any(lessThan(next, ivec2(0))) || any(greaterThanEqual(next, uLevelDims[level])))
    {
      break;
    }
    node = next;
  }
  return hitLayer >= 0;
}

// The colour of a hit: straight RGB and opacity (1, or the merged translucent layer's).
vec4 strataShade(int hitLayer, ivec2 hitCell, vec3 pGrid)
{
  //STRATA::Color::Impl
  //STRATA::Translucency::Merge

  //STRATA::Shading::Impl

  //STRATA::Output::Impl
}

void main()
{
  vec2 ndc = (gl_FragCoord.xy - uViewport.xy) / uViewport.zw * 2.0 - 1.0;
  vec4 n4 = uClipToGrid * vec4(ndc, -1.0, 1.0);
  vec4 f4 = uClipToGrid * vec4(ndc, 1.0, 1.0);
  vec3 o = n4.xyz / n4.w;
  vec3 d = f4.xyz / f4.w - o;

  // Clip the near-to-far segment (t in [0, 1]) to the stack's box.
  vec3 lo = vec3(0.0, 0.0, uZRange.x - uZEps);
  vec3 hi = vec3(uGridMax, uZRange.y + uZEps);
  float tEnter = 0.0, tExit = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] != 0.0)
    {
      float s0 = (lo[a] - o[a]) / d[a];
      float s1 = (hi[a] - o[a]) / d[a];
      tEnter = max(tEnter, min(s0, s1));
      tExit = min(tExit, max(s0, s1));
    }
    else if (o[a] < lo[a] || o[a] > hi[a])
    {
      discard;
    }
  }
  // The region: hits inside it only (the next process's box draws the rest).
  for (int i = 0; i < uNumRegionPlanes; ++i)
  {
    float denom = dot(uRegionPlanes[i].xyz, d);
    float dist = dot(uRegionPlanes[i].xyz, o) + uRegionPlanes[i].w;
    if (denom < 0.0)
    {
      tEnter = max(tEnter, -dist / denom);
    }
    else if (denom > 0.0)
    {
      tExit = min(tExit, -dist / denom);
    }
    else if (dist > 0.0)
    {
      discard;
    }
  }
  //STRATA::Translucency::Start
  if (tEnter > tExit)
  {
    discard;
  }
  float tHit = BIG;
  int hitLayer = -1;
  ivec2 hitCell = ivec2(0);
  if (!strataCast(o, d, tEnter, tExit, tHit, hitLayer, hitCell))
  {
    discard;
  }

  vec3 pGrid = o + tHit * d;
  vec4 clip = uGridToClip * vec4(pGrid, 1.0);
  float ndcDepth = clip.z / clip.w;
  gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndcDepth + gl_DepthRange.near + gl_DepthRange.far);
  //STRATA::Translucency::Depth

  //STRATA::Feedback::Impl

  //STRATA::Translucency::Output
}
