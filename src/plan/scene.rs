//! The scene file of `hairmath plan`: the error budget, what to minimise, the hair the scene
//! contains and its lights, read from TOML. Every error names the file, the line, the dotted
//! key, what is wrong and what is allowed.
//!
//! ```toml
//! budget = 0.05            # the error E against the Chiang far field, > 0
//! cost = "ops"             # "ops" (weighted traced operation counts) or "llvmpipe"
//! [hair]                   # a value (baked), a [min, max] range, or { varying = [min, max] }
//! eumelanin = [0.5, 1.5]
//! pheomelanin = 0.0
//! beta_m = 0.3
//! beta_n = { varying = [0.3, 0.6] }
//! alpha_deg = 2.0
//! eta = 1.55
//! [lights]
//! directional = true
//! environment = "none"     # or "sh": an SH environment with bands l <= environment_sh_lmax
//! environment_sh_lmax = 2
//! ```

use std::path::Path;

use toml::de::{DeInteger, DeTable, DeValue};
use toml::Spanned;

use crate::absorption::Absorption;
use crate::csv::format_number;
use crate::params::{AzimuthalRoughness, CuticleTilt, LongitudinalRoughness, RefractiveIndex};

/// What the planner minimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CostMeasure {
    /// The weighted counts of the shader's traced operations (`cost = "ops"`, the default).
    Ops,
    /// The shader's measured time on Mesa's llvmpipe, the software Vulkan device
    /// (`cost = "llvmpipe"`): the fastest measured of the cheapest compositions by weighted
    /// operations that meet the budget ([`super::PlanSettings::device_candidates`]; the
    /// module documentation of [`super::plan`]).
    Llvmpipe,
}

/// How a hair parameter is given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamRange {
    /// One value, baked into the shader.
    Fixed(f64),
    /// A range of materials, `[min, max]`: the shader takes the value as an argument.
    Range {
        /// The smallest value.
        min: f64,
        /// The largest value.
        max: f64,
    },
    /// A value that varies per pixel, `{ varying = [min, max] }`.
    Varying {
        /// The smallest value.
        min: f64,
        /// The largest value.
        max: f64,
    },
}

impl ParamRange {
    /// The smallest value (a fixed parameter's value).
    pub fn min(&self) -> f64 {
        match *self {
            ParamRange::Fixed(v) => v,
            ParamRange::Range { min, .. } | ParamRange::Varying { min, .. } => min,
        }
    }

    /// The largest value (a fixed parameter's value).
    pub fn max(&self) -> f64 {
        match *self {
            ParamRange::Fixed(v) => v,
            ParamRange::Range { max, .. } | ParamRange::Varying { max, .. } => max,
        }
    }

    /// Whether the value is baked into the shader.
    pub fn is_fixed(&self) -> bool {
        matches!(self, ParamRange::Fixed(_))
    }
}

/// A hair parameter of the scene file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HairKey {
    /// The eumelanin concentration (`eumelanin`, >= 0).
    Eumelanin,
    /// The pheomelanin concentration (`pheomelanin`, >= 0, default 0).
    Pheomelanin,
    /// The longitudinal roughness (`beta_m`, in [1e-16, 1]).
    BetaM,
    /// The azimuthal roughness (`beta_n`, in [1e-16, 1]).
    BetaN,
    /// The cuticle tilt in degrees (`alpha_deg`, |alpha| < 90, default 2).
    AlphaDeg,
    /// The relative index of refraction (`eta`, in (1, 3], default 1.55).
    Eta,
}

impl HairKey {
    /// Every parameter, in the order defaults are filled in.
    pub const ALL: [HairKey; 6] = [
        HairKey::Eumelanin,
        HairKey::Pheomelanin,
        HairKey::BetaM,
        HairKey::BetaN,
        HairKey::AlphaDeg,
        HairKey::Eta,
    ];

    /// The key's name in the `[hair]` table.
    pub fn name(self) -> &'static str {
        match self {
            HairKey::Eumelanin => "eumelanin",
            HairKey::Pheomelanin => "pheomelanin",
            HairKey::BetaM => "beta_m",
            HairKey::BetaN => "beta_n",
            HairKey::AlphaDeg => "alpha_deg",
            HairKey::Eta => "eta",
        }
    }

    /// The key named `name`.
    fn from_name(name: &str) -> Option<HairKey> {
        HairKey::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The value a file that omits the key gets; `None` for a required key.
    fn default_value(self) -> Option<f64> {
        match self {
            HairKey::Pheomelanin => Some(0.0),
            HairKey::AlphaDeg => Some(2.0),
            HairKey::Eta => Some(RefractiveIndex::HUMAN_HAIR.get()),
            HairKey::Eumelanin | HairKey::BetaM | HairKey::BetaN => None,
        }
    }

    /// Checks `value` against the parameter's domain with the crate's validated type, giving
    /// that type's message.
    fn check(self, value: f64) -> Result<(), String> {
        let checked = match self {
            HairKey::Eumelanin => Absorption::from_melanin(value, 0.0).map(drop),
            HairKey::Pheomelanin => Absorption::from_melanin(0.0, value).map(drop),
            HairKey::BetaM => LongitudinalRoughness::new(value).map(drop),
            HairKey::BetaN => AzimuthalRoughness::new(value).map(drop),
            HairKey::AlphaDeg => CuticleTilt::from_degrees(value).map(drop),
            HairKey::Eta => RefractiveIndex::new(value).map(drop),
        };
        checked.map_err(|e| match self {
            HairKey::AlphaDeg => format!(
                "{} is not allowed: alpha_deg is the cuticle tilt in degrees, finite with \
                 |alpha_deg| < 90 ({e})",
                format_number(value)
            ),
            _ => e.to_string(),
        })
    }
}

/// The `[hair]` table: every parameter (defaults filled in), in the order of the file (keys
/// the file omits, which took their defaults, come after those it gives, in the order of
/// [`HairKey::ALL`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneHair {
    params: Vec<(HairKey, ParamRange)>,
}

impl SceneHair {
    /// How the parameter `key` is given.
    pub fn get(&self, key: HairKey) -> ParamRange {
        self.params
            .iter()
            .find(|(k, _)| *k == key)
            .map(|&(_, range)| range)
            .unwrap_or_else(|| unreachable!("a SceneHair holds every HairKey"))
    }

    /// All six parameters, in file order.
    pub fn params(&self) -> &[(HairKey, ParamRange)] {
        &self.params
    }

    /// The keys given as ranges or varying, in file order (the shader's arguments).
    pub fn non_fixed(&self) -> Vec<HairKey> {
        self.params
            .iter()
            .filter(|(_, range)| !range.is_fixed())
            .map(|&(key, _)| key)
            .collect()
    }
}

/// The environment light of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Environment {
    /// No environment light (`environment = "none"`, the default).
    None,
    /// An environment in spherical harmonics (`environment = "sh"`).
    Sh {
        /// The highest band l (`environment_sh_lmax`, 0 to 8, default 2).
        lmax: u32,
    },
}

/// The `[lights]` table: at least one light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lights {
    /// Whether the scene has directional lights (`directional`, default true).
    pub directional: bool,
    /// The environment light.
    pub environment: Environment,
}

/// A scene file of `hairmath plan`.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The error E against the Chiang far field the plan must stay within, > 0.
    pub budget: f64,
    /// What the planner minimises.
    pub cost: CostMeasure,
    /// The hair the scene contains.
    pub hair: SceneHair,
    /// The scene's lights.
    pub lights: Lights,
}

impl Scene {
    /// Parses a scene file's text; `source` names the file in error messages.
    ///
    /// ```
    /// use hairmath::plan::{HairKey, ParamRange, Scene};
    ///
    /// let text = "budget = 0.05\n[hair]\neumelanin = 1.3\nbeta_m = 0.3\nbeta_n = [0.3, 0.6]\n";
    /// let scene = Scene::parse(text, "scene.toml")?;
    /// let beta_n = ParamRange::Range { min: 0.3, max: 0.6 };
    /// assert_eq!(scene.hair.get(HairKey::BetaN), beta_n);
    /// let bad = Scene::parse("budget = 0\n", "scene.toml").unwrap_err();
    /// assert_eq!(
    ///     bad.to_string(),
    ///     "scene.toml:1: budget: 0 is not allowed: the budget is a finite error E > 0"
    /// );
    /// # Ok::<(), hairmath::plan::SceneError>(())
    /// ```
    ///
    /// # Errors
    /// A [`SceneError`] for invalid TOML, an unknown key, a value of the wrong type or out of
    /// its domain, or a missing required key.
    pub fn parse(text: &str, source: &str) -> Result<Scene, SceneError> {
        let src = Source { text, file: source };
        let root = DeTable::parse(text).map_err(|e| src.syntax(&e))?;
        let top = Table::new(
            src,
            String::new(),
            0,
            root.get_ref(),
            "a scene file",
            &TOP_KEYS,
        )?;
        let budget = budget(top.required("budget", MISSING_BUDGET)?)?;
        let cost = top.field("cost").map(cost).transpose()?;
        let hair = hair(top.required("hair", MISSING_HAIR)?)?;
        let lights = lights(top.field("lights"))?;
        Ok(Scene {
            budget,
            cost: cost.unwrap_or(CostMeasure::Ops),
            hair,
            lights,
        })
    }

    /// Reads and parses the file at `path` (an unreadable file is a [`SceneError`] too, at
    /// line 0). At most [`MAX_SCENE_BYTES`] are read, so that a path such as `/dev/zero`
    /// cannot make it read without end.
    ///
    /// # Errors
    /// As [`Scene::parse`], and a file that cannot be read as UTF-8 text or is longer than
    /// [`MAX_SCENE_BYTES`].
    pub fn read(path: &Path) -> Result<Scene, SceneError> {
        use std::io::Read;
        let file = path.display().to_string();
        let unreadable = |message: String| SceneError {
            file: file.clone(),
            line: 0,
            key: String::new(),
            message,
        };
        let mut text = String::new();
        std::fs::File::open(path)
            .and_then(|f| f.take(MAX_SCENE_BYTES as u64 + 1).read_to_string(&mut text))
            .map_err(|e| unreadable(format!("cannot read the scene file: {e}")))?;
        if text.len() > MAX_SCENE_BYTES {
            return Err(unreadable(format!(
                "the scene file is longer than {MAX_SCENE_BYTES} bytes (the limit of a scene \
                 file; the example scenes have a few hundred)"
            )));
        }
        Scene::parse(&text, &file)
    }
}

/// The longest scene file [`Scene::read`] accepts, in bytes (1 MiB).
pub const MAX_SCENE_BYTES: usize = 1 << 20;

/// A scene file that cannot be used: where, which key, what is wrong and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}: {key}: {message}")]
pub struct SceneError {
    /// The file, as the caller named it.
    pub file: String,
    /// The 1-based line of the offending key or value (0 for a file that cannot be read).
    pub line: usize,
    /// The dotted key, such as `hair.beta_n` or `budget`; empty for a syntax error.
    pub key: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

/// The keys of the top level.
const TOP_KEYS: [&str; 4] = ["budget", "cost", "hair", "lights"];
/// The keys of `[lights]`.
const LIGHT_KEYS: [&str; 3] = ["directional", "environment", "environment_sh_lmax"];
/// The message of a missing budget.
const MISSING_BUDGET: &str =
    "missing; a scene file needs budget = E, the error E > 0 against the Chiang far field";
/// The message of a missing `[hair]` table.
const MISSING_HAIR: &str =
    "missing; a scene file needs a [hair] table giving at least eumelanin, beta_m and beta_n";
/// What a hair parameter may be.
const HAIR_VALUE: &str = "a number, a [min, max] range or { varying = [min, max] }";
/// What a range may be.
const RANGE: &str = "[min, max], two numbers";
/// What the cost may be.
const COST: &str = "\"ops\" (weighted traced operation counts) or \"llvmpipe\"";
/// What the environment may be.
const ENVIRONMENT: &str = "\"none\" or \"sh\" (an SH environment)";
/// The largest SH band of an environment.
const MAX_LMAX: u32 = 8;

/// The text being parsed and the name of its file, for locating errors.
#[derive(Clone, Copy)]
struct Source<'a> {
    text: &'a str,
    file: &'a str,
}

impl Source<'_> {
    /// The error at byte offset `at` of the text.
    fn error(&self, at: usize, key: &str, message: String) -> SceneError {
        let before = &self.text.as_bytes()[..at.min(self.text.len())];
        SceneError {
            file: self.file.to_owned(),
            line: 1 + before.iter().filter(|&&b| b == b'\n').count(),
            key: key.to_owned(),
            message,
        }
    }

    /// The error of text that is not TOML.
    fn syntax(&self, e: &toml::de::Error) -> SceneError {
        let at = e.span().map_or(0, |span| span.start);
        let message = format!(
            "not valid TOML (a scene file is a TOML document): {}",
            e.message()
        );
        self.error(at, "", message)
    }
}

/// A key of the file and its value, or an element of an array value under its array's key.
struct Field<'a> {
    src: Source<'a>,
    /// The dotted key.
    key: String,
    /// The key as the table spells it.
    name: &'a str,
    /// Where the key (or the element) starts.
    key_at: usize,
    value: &'a Spanned<DeValue<'a>>,
}

impl<'a> Field<'a> {
    /// The error at the key.
    fn at_key(&self, message: String) -> SceneError {
        self.src.error(self.key_at, &self.key, message)
    }

    /// The error at the value.
    fn at_value(&self, message: String) -> SceneError {
        self.src.error(self.value.span().start, &self.key, message)
    }

    /// The error of a value of the wrong type.
    fn found(&self, expected: &str) -> SceneError {
        let found = kind(self.value.get_ref());
        self.at_key(format!("expected {expected}, found {found}"))
    }

    /// The element `value` of this field's array, under this field's key.
    fn element(&self, value: &'a Spanned<DeValue<'a>>) -> Field<'a> {
        Field {
            key: self.key.clone(),
            key_at: value.span().start,
            value,
            ..*self
        }
    }

    /// The value as a number (an integer or a float).
    fn number(&self, expected: &str) -> Result<f64, SceneError> {
        let parsed = match self.value.get_ref() {
            DeValue::Integer(i) => integer(i).map(|n| n as f64),
            DeValue::Float(f) => f.as_str().parse().ok(),
            _ => return Err(self.found(expected)),
        };
        parsed.ok_or_else(|| {
            self.at_value(format!("not a representable number; expected {expected}"))
        })
    }

    /// The value as a boolean.
    fn boolean(&self) -> Result<bool, SceneError> {
        match self.value.get_ref() {
            DeValue::Boolean(b) => Ok(*b),
            _ => Err(self.found("a boolean, true or false")),
        }
    }

    /// The value as a string.
    fn string(&self, expected: &str) -> Result<&'a str, SceneError> {
        match self.value.get_ref() {
            DeValue::String(s) => Ok(s.as_ref()),
            _ => Err(self.found(expected)),
        }
    }

    /// The value as the table `title`, whose keys must be among `allowed`.
    fn table(&self, title: &str, allowed: &[&str]) -> Result<Table<'a>, SceneError> {
        match self.value.get_ref() {
            DeValue::Table(t) => Table::of(self, t, title, allowed),
            _ => Err(self.found(&format!("a table {title}"))),
        }
    }

    /// The value as an array `[min, max]` of two numbers (not yet ordered).
    fn pair(&self) -> Result<(f64, f64), SceneError> {
        let DeValue::Array(items) = self.value.get_ref() else {
            return Err(self.found(RANGE));
        };
        match &items[..] {
            [min, max] => Ok((
                self.element(min).number(RANGE)?,
                self.element(max).number(RANGE)?,
            )),
            other => Err(self.at_value(format!("expected {RANGE}, found {} values", other.len()))),
        }
    }
}

/// A table of the file: its dotted name, where it starts and its keys in file order, every key
/// checked against the allowed ones.
struct Table<'a> {
    src: Source<'a>,
    /// The dotted name; empty for the top level.
    name: String,
    /// Where the table starts (its header, for a `[table]`).
    start: usize,
    entries: Vec<Field<'a>>,
}

impl<'a> Table<'a> {
    /// The table `table` named `name` starting at `start`, an error at its first key (in file
    /// order) that is not among `allowed`; `title` names the table in that error.
    fn new(
        src: Source<'a>,
        name: String,
        start: usize,
        table: &'a DeTable<'a>,
        title: &str,
        allowed: &[&str],
    ) -> Result<Table<'a>, SceneError> {
        let mut entries: Vec<Field<'a>> = table
            .iter()
            .map(|(key, value)| Field {
                src,
                key: dotted(&name, key.get_ref()),
                name: key.get_ref(),
                key_at: key.span().start,
                value,
            })
            .collect();
        entries.sort_by_key(|f| f.key_at);
        if let Some(unknown) = entries.iter().find(|f| !allowed.contains(&f.name)) {
            let keys = allowed.join(", ");
            return Err(unknown.at_key(format!("unknown key; the keys of {title} are {keys}")));
        }
        Ok(Table {
            src,
            name,
            start,
            entries,
        })
    }

    /// The value of `field`, the table `table`, as [`Table::new`] checks it.
    fn of(
        field: &Field<'a>,
        table: &'a DeTable<'a>,
        title: &str,
        allowed: &[&str],
    ) -> Result<Table<'a>, SceneError> {
        let start = field.value.span().start;
        Table::new(field.src, field.key.clone(), start, table, title, allowed)
    }

    /// The key `name`, if the file gives it.
    fn field(&self, name: &str) -> Option<&Field<'a>> {
        self.entries.iter().find(|f| f.name == name)
    }

    /// The key `name`, or the error `missing` at the table's start.
    fn required(&self, name: &str, missing: &str) -> Result<&Field<'a>, SceneError> {
        self.field(name).ok_or_else(|| {
            self.src
                .error(self.start, &dotted(&self.name, name), missing.to_owned())
        })
    }
}

/// `name` under the table `table` ("" for the top level).
fn dotted(table: &str, name: &str) -> String {
    if table.is_empty() {
        name.to_owned()
    } else {
        format!("{table}.{name}")
    }
}

/// The type of a value, with its article, for messages.
fn kind(value: &DeValue<'_>) -> &'static str {
    match value {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date-time",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

/// The value of a TOML integer, if it fits an `i128`.
fn integer(i: &DeInteger<'_>) -> Option<i128> {
    i128::from_str_radix(i.as_str(), i.radix()).ok()
}

/// The budget: a finite number > 0.
fn budget(field: &Field<'_>) -> Result<f64, SceneError> {
    let budget = field.number("a number")?;
    if budget.is_finite() && budget > 0.0 {
        Ok(budget)
    } else {
        Err(field.at_value(format!(
            "{} is not allowed: the budget is a finite error E > 0",
            format_number(budget)
        )))
    }
}

/// The cost measure.
fn cost(field: &Field<'_>) -> Result<CostMeasure, SceneError> {
    match field.string(COST)? {
        "ops" => Ok(CostMeasure::Ops),
        "llvmpipe" => Ok(CostMeasure::Llvmpipe),
        other => Err(field.at_value(format!("{other:?} is not a cost; the cost is {COST}"))),
    }
}

/// The `[hair]` table.
fn hair(field: &Field<'_>) -> Result<SceneHair, SceneError> {
    let table = field.table("[hair]", &HairKey::ALL.map(HairKey::name))?;
    let mut params = Vec::with_capacity(HairKey::ALL.len());
    for f in &table.entries {
        if let Some(key) = HairKey::from_name(f.name) {
            params.push((key, param_range(f, key)?));
        }
    }
    for key in HairKey::ALL {
        if params.iter().all(|&(k, _)| k != key) {
            let value = key
                .default_value()
                .ok_or_else(|| missing_hair(&table, key))?;
            params.push((key, ParamRange::Fixed(value)));
        }
    }
    Ok(SceneHair { params })
}

/// The error of a required hair parameter the file omits.
fn missing_hair(table: &Table<'_>, key: HairKey) -> SceneError {
    let message = "missing; [hair] must give eumelanin, beta_m and beta_n (pheomelanin, \
                   alpha_deg and eta have defaults)";
    let key = dotted(&table.name, key.name());
    table.src.error(table.start, &key, message.to_owned())
}

/// A hair parameter: a number, `[min, max]` or `{ varying = [min, max] }`, in its domain.
fn param_range(field: &Field<'_>, key: HairKey) -> Result<ParamRange, SceneError> {
    let range = match field.value.get_ref() {
        DeValue::Array(_) => {
            let (min, max) = field.pair()?;
            ParamRange::Range { min, max }
        }
        DeValue::Table(t) => {
            let table = Table::of(field, t, "{ varying = [min, max] }", &["varying"])?;
            let missing = "missing; a per-pixel parameter is { varying = [min, max] }";
            let (min, max) = table.required("varying", missing)?.pair()?;
            ParamRange::Varying { min, max }
        }
        _ => ParamRange::Fixed(field.number(HAIR_VALUE)?),
    };
    for value in [range.min(), range.max()] {
        key.check(value).map_err(|e| field.at_value(e))?;
    }
    if range.min() > range.max() {
        let (min, max) = (range.min(), range.max());
        let message = format!(
            "min {} > max {}: a range is [min, max] with min <= max",
            format_number(min),
            format_number(max)
        );
        return Err(field.at_value(message));
    }
    Ok(range)
}

/// The `[lights]` table, if the file has one (the defaults otherwise).
fn lights(field: Option<&Field<'_>>) -> Result<Lights, SceneError> {
    let table = field
        .map(|f| f.table("[lights]", &LIGHT_KEYS))
        .transpose()?;
    let get = |name: &str| table.as_ref().and_then(|t| t.field(name));
    let directional = get("directional").map(Field::boolean).transpose()?;
    let sh = get("environment").map(environment_is_sh).transpose()?;
    let lmax = get("environment_sh_lmax").map(sh_lmax).transpose()?;
    let lights = Lights {
        directional: directional.unwrap_or(true),
        environment: match sh {
            Some(true) => Environment::Sh {
                lmax: lmax.unwrap_or(2),
            },
            _ => Environment::None,
        },
    };
    match &table {
        Some(t) if lights == NO_LIGHTS => {
            Err(t.src.error(t.start, &t.name, NO_LIGHTS_MESSAGE.to_owned()))
        }
        _ => Ok(lights),
    }
}

/// The lights of a scene without any.
const NO_LIGHTS: Lights = Lights {
    directional: false,
    environment: Environment::None,
};

/// The message of a scene without lights.
const NO_LIGHTS_MESSAGE: &str = "no light: directional = false with environment = \"none\"; a \
                                 scene needs directional = true, environment = \"sh\", or both";

/// Whether the environment is `"sh"` (rather than `"none"`).
fn environment_is_sh(field: &Field<'_>) -> Result<bool, SceneError> {
    match field.string(ENVIRONMENT)? {
        "none" => Ok(false),
        "sh" => Ok(true),
        other => Err(field.at_value(format!(
            "{other:?} is not an environment; the environment is {ENVIRONMENT}"
        ))),
    }
}

/// The highest SH band of the environment, an integer in `0..=MAX_LMAX`.
fn sh_lmax(field: &Field<'_>) -> Result<u32, SceneError> {
    let expected = format!("an integer in 0..={MAX_LMAX}");
    let DeValue::Integer(i) = field.value.get_ref() else {
        return Err(field.found(&expected));
    };
    integer(i)
        .and_then(|n| u32::try_from(n).ok())
        .filter(|&n| n <= MAX_LMAX)
        .ok_or_else(|| {
            field.at_value(format!(
                "{} is not allowed: environment_sh_lmax, the highest SH band, is {expected}",
                i.as_str()
            ))
        })
}
