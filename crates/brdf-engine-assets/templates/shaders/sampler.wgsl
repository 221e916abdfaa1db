fn {{ name }}(lut: texture_2d<f32>, samp: sampler, p0: f32, p1: f32) -> {{ "f32" if nc == 1 else "vec2<f32>" }} {
    let x0 = clamp(p0, {{ a0.lo }}, {{ a0.hi }});
    let x1 = clamp(p1, {{ a1.lo }}, {{ a1.hi }});
    let t0 = clamp({{ a0.t }}, 0.0, 1.0);
    let t1 = clamp({{ a1.t }}, 0.0, 1.0);
    let uv = vec2<f32>({{ a0.u }}, {{ a1.u }});
{% if nc == 1 %}
    let c = textureSampleLevel(lut, samp, uv, 0.0).r;
    return {{ off[0] }} + {{ scale[0] }} * c;
{% else %}
    let c = textureSampleLevel(lut, samp, uv, 0.0).rg;
    return vec2<f32>({{ off[0] }}, {{ off[1] }}) + vec2<f32>({{ scale[0] }}, {{ scale[1] }}) * c;
{% endif %}
}
