//! The club presets: the seed's driver and 7-iron (Table 3.1, equal to `ClubSpec::driver()` and
//! `ClubSpec::iron7()`) and a set built around them from published specs, each a TOML club file in
//! `clubs/presets/` embedded in the binary (the file beside each number says where it comes from, or how it is
//! derived; docs/club-files.md tables them).
//!
//! A preset loads exactly as its file would (`impactd predict --club clubs/presets/sw.toml` equals `--club sw`),
//! so a preset's content hash (`wire::ClubRef`) is the hash of those bytes.

use super::{ClubFile, ClubSpec, EquipmentError, LoadedClub};

/// One preset: the name users type, the other names it answers to, and its club file.
pub struct Preset {
    /// The name users type (`iron7`).
    pub name: &'static str,
    /// Other names it answers to (`7i`).
    pub aliases: &'static [&'static str],
    /// Its club file's text (`clubs/presets/<name>.toml`).
    pub text: &'static str,
}

macro_rules! file {
    ($name:literal, $aliases:expr) => {
        Preset {
            name: $name,
            aliases: $aliases,
            text: include_str!(concat!("../../../../clubs/presets/", $name, ".toml")),
        }
    };
}

/// Every preset, from the longest club to the shortest.
pub const PRESETS: &[Preset] = &[
    file!("driver", &["1w", "dr"]),
    file!("wood3", &["3w", "3wood"]),
    file!("hybrid", &["hy", "3h"]),
    file!("iron4", &["4i", "4iron"]),
    file!("iron5", &["5i", "5iron"]),
    file!("iron6", &["6i", "6iron"]),
    file!("iron7", &["7i", "7iron"]),
    file!("iron8", &["8i", "8iron"]),
    file!("iron9", &["9i", "9iron"]),
    file!("pw", &["pitching_wedge"]),
    file!("gw", &["gap_wedge", "aw"]),
    file!("sw", &["sand_wedge"]),
    file!("lw", &["lob_wedge"]),
];

/// The preset a name or alias stands for.
pub fn find(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name == name || p.aliases.contains(&name))
}

/// The names of the presets, comma-separated (for errors and help).
pub fn names() -> String {
    PRESETS.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
}

impl Preset {
    /// The club with its model sections.
    pub fn load(&self) -> Result<LoadedClub, EquipmentError> {
        ClubFile::parse(self.text)
    }

    /// The bytes that identify it: its file's.
    pub fn bytes(&self) -> &'static [u8] {
        self.text.as_bytes()
    }
}

impl ClubSpec {
    /// A preset by name or alias (`driver`, `wood3`, `hybrid`, `iron4` ... `iron9`, `pw`, `gw`, `sw`, `lw`;
    /// [`find`]).
    pub fn preset(name: &str) -> Result<Self, EquipmentError> {
        find(name).ok_or_else(|| EquipmentError::UnknownPreset(name.to_string()))?.load().map(|loaded| loaded.club)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every preset loads, under its own name, and the set runs from the longest club to the shortest: loft and
    /// head mass never fall from one club to the next (the 7 g step of iron heads, lofts of the P790 set).
    #[test]
    fn every_preset_loads_in_order() {
        let mut last = (0.0, 0.0);
        for p in PRESETS {
            let club = p.load().unwrap().club;
            assert_eq!(club.name, p.name);
            assert!(find(p.name).is_some() && p.aliases.iter().all(|a| find(a).map(|f| f.name) == Some(p.name)));
            assert!(club.loft_deg() > last.0 && club.mass_kg >= last.1, "{}", p.name);
            last = (club.loft_deg(), club.mass_kg);
        }
        assert!(find("putter").is_none());
        assert_eq!(find("driver").unwrap().load().unwrap().club, super::super::ClubSpec::driver());
        // The iron7 preset's club is the seed's (Table 3.1); its file adds the slip model's obliquity law only.
        assert_eq!(find("iron7").unwrap().load().unwrap().club, super::super::ClubSpec::iron7());
        // The other irons and wedges carry the shaft's share about the heel-toe axis (research/scripts/shaft-share.py).
        for p in ["iron4", "iron5", "iron6", "iron8", "iron9", "pw", "gw", "sw", "lw"] {
            assert!(find(p).unwrap().load().unwrap().club.shaft_heel_toe_inertia_kg_m2 > 0.0, "{p}");
        }
    }

    /// Every iron and wedge preset uses the same slip physics with its own club's numbers (issue 47): the rise of
    /// the tangential restitution with obliquity (Cross, "Grip-slip behavior of a bouncing ball", Am. J. Phys. 70,
    /// 2002, as the seed's chapter 2 cites it; `impact::impulse::oblique`). The `iron7` preset, the seed's head,
    /// did not carry it, so the slip model's spin changed character between the 6-, 7- and 8-iron.
    #[test]
    fn every_iron_and_wedge_carries_the_obliquity_law() {
        for p in ["iron4", "iron5", "iron6", "iron7", "iron8", "iron9", "pw", "gw", "sw", "lw"] {
            let loaded = find(p).unwrap().load().unwrap();
            let tuning = crate::impact::impulse::ImpulseTuning::from_sections(&loaded.club, &loaded.sections).unwrap();
            let rise = tuning.slip_oblique.unwrap_or_else(|| panic!("{p}: no obliquity law for the slip model"));
            assert_eq!((rise.from_deg, rise.full_deg, rise.e_t), (32.8, 40.0, 0.25), "{p}");
        }
    }

    /// The irons' CG keeps the seed 7-iron's place relative to the face: 5.57 mm behind the face plane and
    /// 2.35 mm below the face centre along the face, whatever the loft (the derivation in each file).
    #[test]
    fn iron_cg_keeps_its_depth_behind_the_lofted_face() {
        for p in PRESETS.iter().filter(|p| p.name != "driver" && p.name != "wood3" && p.name != "hybrid") {
            let club = p.load().unwrap().club;
            let l = club.face.loft_rad;
            let c = club.face.center_m;
            let depth_mm = (c.x * l.cos() + c.y * l.sin()) * 1e3;
            let up_mm = (-c.x * l.sin() + c.y * l.cos()) * 1e3;
            assert!((depth_mm - 5.572).abs() < 0.01 && (up_mm - 2.347).abs() < 0.01, "{}: {depth_mm} {up_mm}", p.name);
        }
    }

    /// The second moments of mass of the seed's 7-iron (Table 3.1) from its own tensor about the CG: for any body,
    /// `integral y^2 dm = (I_xx + I_zz - I_yy) / 2` and `integral x^2 dm = (I_yy + I_zz - I_xx) / 2` (x forward,
    /// y up, z toward the toe). They put its mass 9.1 mm rms above or below the CG and 11.6 mm before or behind
    /// it, deeper than tall, where an iron head is taller than deep: the published heel-toe inertia (576.6 g cm2,
    /// the `I_zz` that sets a high or low strike's effective mass) is the number research/offcentre-monitors.md
    /// questions, without a published one to replace it.
    #[test]
    fn the_seed_iron7_tensor_puts_its_mass_deeper_than_tall() {
        let club = ClubSpec::iron7();
        let i = club.inertia_kg_m2 * 1e7;
        let (yy_g_cm2, xx_g_cm2) =
            ((i[(0, 0)] + i[(2, 2)] - i[(1, 1)]) / 2.0, (i[(1, 1)] + i[(2, 2)] - i[(0, 0)]) / 2.0);
        assert!((yy_g_cm2 - 219.8).abs() < 0.1 && (xx_g_cm2 - 356.8).abs() < 0.1, "{yy_g_cm2} {xx_g_cm2}");
        let rms_mm = |second_g_cm2: f64| (second_g_cm2 / (club.mass_kg * 1e3)).sqrt() * 10.0;
        assert!((rms_mm(yy_g_cm2) - 9.1).abs() < 0.05 && (rms_mm(xx_g_cm2) - 11.6).abs() < 0.05);
    }
}
