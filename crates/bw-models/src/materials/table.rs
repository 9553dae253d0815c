//! Common engineering materials with typical values and the sources they are taken from.
//! Each is one grade and temper; a user's own values take precedence over these (and should,
//! where the grade differs).

use super::Material;

/// One entry of [`MATERIALS`]: a name a description uses (`material = "alumina"`), the
/// values, and where they come from.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct Entry {
    /// The name (`"steel-aisi-52100"`).
    pub name: &'static str,
    /// What exactly it is (grade, temper).
    pub grade: &'static str,
    /// The values.
    pub material: Material,
    /// The published source of the values.
    pub source: &'static str,
}

const ASM: &str = "ASM Aerospace Specification Metals, material data sheet (asm.matweb.com)";
const MATWEB: &str = "MatWeb material property data (matweb.com), typical values";

const fn entry(
    name: &'static str,
    grade: &'static str,
    (youngs_modulus, poisson, density, yield_strength): (f64, f64, f64, Option<f64>),
    source: &'static str,
) -> Entry {
    Entry {
        name,
        grade,
        material: Material {
            youngs_modulus,
            poisson,
            density,
            yield_strength,
        },
        source,
    }
}

/// The table: Young's modulus (Pa), Poisson's ratio, density (kg/m³), yield strength (Pa;
/// `None` for a brittle material that fractures before it yields, taken as elastic).
pub const MATERIALS: [Entry; 14] = [
    entry(
        "steel-aisi-52100",
        "AISI 52100 bearing steel, hardened",
        (210e9, 0.30, 7810.0, Some(2.03e9)),
        MATWEB,
    ),
    entry(
        "steel-aisi-1045",
        "AISI 1045 carbon steel, cold drawn",
        (205e9, 0.29, 7870.0, Some(530e6)),
        MATWEB,
    ),
    entry(
        "stainless-304",
        "AISI 304 stainless steel, annealed",
        (193e9, 0.29, 8000.0, Some(215e6)),
        ASM,
    ),
    entry(
        "aluminium-6061-t6",
        "aluminium alloy 6061-T6",
        (68.9e9, 0.33, 2700.0, Some(276e6)),
        ASM,
    ),
    entry(
        "aluminium-7075-t6",
        "aluminium alloy 7075-T6",
        (71.7e9, 0.33, 2810.0, Some(503e6)),
        ASM,
    ),
    entry(
        "aluminium-6082-t6",
        "aluminium alloy 6082-T6",
        (70e9, 0.33, 2700.0, Some(260e6)),
        MATWEB,
    ),
    entry(
        "alumina",
        "aluminium oxide, 99.5 % Al2O3",
        (370e9, 0.22, 3890.0, None),
        MATWEB,
    ),
    entry(
        "glass-soda-lime",
        "soda-lime glass",
        (72e9, 0.23, 2500.0, None),
        MATWEB,
    ),
    entry(
        "brass-c36000",
        "free-cutting brass C36000, half hard",
        (97e9, 0.31, 8500.0, Some(310e6)),
        MATWEB,
    ),
    entry(
        "copper-c11000",
        "copper C11000, annealed",
        (115e9, 0.31, 8890.0, Some(69e6)),
        MATWEB,
    ),
    entry(
        "titanium-ti6al4v",
        "titanium alloy Ti-6Al-4V (grade 5), annealed",
        (113.8e9, 0.342, 4430.0, Some(880e6)),
        ASM,
    ),
    entry(
        "tungsten-carbide",
        "tungsten carbide, 6 % cobalt",
        (600e9, 0.22, 14900.0, None),
        MATWEB,
    ),
    entry(
        "pmma",
        "poly(methyl methacrylate), cast",
        (3.1e9, 0.37, 1190.0, Some(70e6)),
        MATWEB,
    ),
    entry(
        "ptfe",
        "polytetrafluoroethylene, unfilled",
        (0.5e9, 0.46, 2200.0, Some(10e6)),
        MATWEB,
    ),
];

/// The entry called `name`.
pub fn material(name: &str) -> Option<&'static Entry> {
    MATERIALS.iter().find(|e| e.name == name)
}

/// The names of every entry, comma-separated.
pub fn material_names() -> String {
    let names: Vec<&str> = MATERIALS.iter().map(|e| e.name).collect();
    names.join(", ")
}
