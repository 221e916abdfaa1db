/* The LUT files from assets/, embedded byte for byte (assemble with -Wa,-I<assets dir>). */
    .section .rodata.brdf_tables, "a"
    .balign 4
    .global table_g, table_g_end
table_g:
    .incbin "g_modified_sigma0.3.blut"
table_g_end:
    .type table_g, %object
    .size table_g, table_g_end - table_g
    .balign 4
    .global table_dfg, table_dfg_end
table_dfg:
    .incbin "dfg_ggx.blut"
table_dfg_end:
    .type table_dfg, %object
    .size table_dfg, table_dfg_end - table_dfg
    .balign 4
    .global table_e, table_e_end
table_e:
    .incbin "kc_e_ggx.blut"
table_e_end:
    .type table_e, %object
    .size table_e, table_e_end - table_e
    .balign 4
    .global table_eavg, table_eavg_end
table_eavg:
    .incbin "kc_eavg_ggx.blut"
table_eavg_end:
    .type table_eavg, %object
    .size table_eavg, table_eavg_end - table_eavg
    .section .note.GNU-stack, "", %progbits
