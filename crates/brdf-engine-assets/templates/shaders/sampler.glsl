{{ "float" if nc == 1 else "vec2" }} {{ name }}(sampler2D lut, float p0, float p1) {
    float x0 = clamp(p0, {{ a0.lo }}, {{ a0.hi }});
    float x1 = clamp(p1, {{ a1.lo }}, {{ a1.hi }});
    float t0 = clamp({{ a0.t }}, 0.0, 1.0);
    float t1 = clamp({{ a1.t }}, 0.0, 1.0);
    vec2 uv = vec2({{ a0.u }}, {{ a1.u }});
{% if nc == 1 %}
    float c = texture(lut, uv).r;
    return {{ off[0] }} + {{ scale[0] }} * c;
{% else %}
    vec2 c = texture(lut, uv).rg;
    return vec2({{ off[0] }}, {{ off[1] }}) + vec2({{ scale[0] }}, {{ scale[1] }}) * c;
{% endif %}
}
