//! The club-file sections the models read, each with its fields: the one list `impactd models --sections`
//! prints and docs/club-files.md is generated from (`scripts/registry-docs.sh`). Which models read a section is
//! the registry's (`MODELS` in registry.rs).

/// One club-file section.
pub struct SectionDoc {
    /// The section's name in a club file (`[name]`).
    pub name: &'static str,
    /// Its fields and what they mean, one line each.
    pub fields: &'static [&'static str],
}

/// Every section a model reads, in the order a club file lists them.
pub const SECTIONS: &[SectionDoc] = &[
    SectionDoc { name: "adjusted", fields: &["delta_mass_kg, ball_cg_shift_m"] },
    SectionDoc {
        name: "slip",
        fields: &[
            "e_y, e_z; optionally oblique_from_deg, oblique_full_deg,",
            "oblique_e_t together (Cross's grip rising with the strike's",
            "obliquity, impact/impulse/oblique.rs; every iron and wedge",
            "preset carries it, research/wedge-spin.md)",
        ],
    },
    SectionDoc {
        name: "continuous",
        fields: &[
            "reading (\"one_cycle\", default, or \"table\":",
            "Table 3.5 as printed), then any of k_v_n_per_m3, d_s_per_m, mu,",
            "k_ball_nm_per_rad, c_ball_nms_per_rad, cover_thickness_m, v_tr_mps",
            "(`ground` without this section: Table 3.5 as printed, the ball its findings",
            "in research/ground-findings.md are measured with)",
        ],
    },
    SectionDoc { name: "maw", fields: &["e_pa, nu, d_s_per_m, mu, rings (default 20)"] },
    SectionDoc {
        name: "arakawa",
        fields: &[
            "e_pa, nu, d_s_per_m, mu, eta_n_s_per_m2,",
            "reading (\"envelope\", default, \"friction\" or \"literal\")",
        ],
    },
    SectionDoc { name: "soil", fields: &["preset = \"soft|medium|firm\", or a soil file's fields"] },
    SectionDoc {
        name: "sole",
        fields: &[
            "lie_deg, sole_width_m, sole_length_m, bounce_deg, sole_radius_m,",
            "leading_edge_below_face_centre_m, shaft_tip_from_cg_m, toe_down_deg (the sole's",
            "heel-toe tilt at delivery, toe down +; level by default) (typical 7-iron otherwise)",
        ],
    },
    SectionDoc { name: "shaft", fields: &["stations, youngs_modulus_pa, poisson_ratio, density_kg_m3, mass_kg"] },
];
