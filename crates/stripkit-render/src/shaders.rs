//! The renderer's GLSL ES programs, one source with switches.
//!
//! - Positions morph: `mix(a_pos, a_pos2, u_t)`; a mesh without a second position buffer
//!   binds the first one twice.
//! - `u_heavy` iterations of a 4x4 matrix blend stand for a skinning vertex shader. The
//!   matrices are uniforms, so the compiler cannot fold them away.
//! - `COUNT` adds one atomic increment per vertex-shader invocation to a storage
//!   buffer: how many vertices the GPU shaded, which shows its reuse of shaded vertices.
//! - The fragment shader lights with the vertex normal (`u_shading == 0`), the face
//!   normal from screen-space derivatives (`1`), or not at all (`2`), times the vertex colour.

pub(crate) fn vertex(version: &str, count: bool) -> String {
    let count_decl = if count {
        "layout(std430, binding = 0) buffer Counter { uint invocations; };\n"
    } else {
        ""
    };
    let count_stmt = if count { "    atomicAdd(invocations, 1u);\n" } else { "" };
    format!(
        "#version {version}
precision highp float;
precision highp int;
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_pos2;
layout(location = 2) in vec3 a_nrm;
layout(location = 3) in vec4 a_col;
uniform mat4 u_mvp;
uniform float u_t;
uniform int u_heavy;
uniform mat4 u_bone[4];
out vec3 v_nrm;
out vec3 v_pos;
out vec4 v_col;
{count_decl}void main() {{
    vec3 p = mix(a_pos, a_pos2, u_t);
    vec3 n = a_nrm;
    for (int i = 0; i < u_heavy; i++) {{
        mat4 m = u_bone[i & 3];
        p = (m * vec4(p, 1.0)).xyz;
        n = mat3(m) * n;
    }}
{count_stmt}    v_nrm = n;
    v_pos = p;
    v_col = a_col;
    gl_Position = u_mvp * vec4(p, 1.0);
}}
"
    )
}

pub(crate) fn fragment(version: &str) -> String {
    format!(
        "#version {version}
precision highp float;
in vec3 v_nrm;
in vec3 v_pos;
in vec4 v_col;
uniform int u_shading;
uniform vec3 u_light;
out vec4 o_col;
void main() {{
    vec3 n;
    if (u_shading == 1) {{
        n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
    }} else {{
        n = normalize(v_nrm);
    }}
    float l = u_shading == 2 ? 1.0 : 0.3 + 0.7 * abs(dot(n, u_light));
    o_col = vec4(v_col.rgb * l, 1.0);
}}
"
    )
}
