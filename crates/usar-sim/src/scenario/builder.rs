//! A scenario in code: [`ScenarioSpec::builder`] takes plain numbers and validates once, at
//! [`ScenarioBuilder::build`].
//!
//! Every field with a default in the file has the same default here (mission, navigation,
//! collision, sim, needs weights, wall thickness, report; no debris, no radiation), so a
//! scenario in code needs the lines its RON needs. A bad number is not a panic at the call
//! that gave it: `build` returns the first one as a one-line [`ScenarioError`] naming its
//! field, `origin: field: message` with the scenario's name as the origin (no line or column:
//! there is no file), followed by every rule of validation ([`ScenarioSpec::validate`]).

use super::draft::{KindDraft, TaskDraft, Xy, circle, missing};
use super::edit::{field_error, number_at, with_origin};
use super::error::ScenarioError;
use super::params::{
    Arena, CollisionParams, MissionParams, NavigationParams, NeedsWeights, SimParams,
};
use super::spec::{
    DebrisFieldSpec, DebrisSpec, RadiationZoneSpec, ReportSpec, RestStationsSpec, ScenarioSpec,
    TaskQuotas,
};
use super::suggest::did_you_mean;
use super::validated::Scenario;

/// A scenario being written in code; see the module docs and [`ScenarioSpec::builder`].
#[derive(Debug, Clone)]
pub struct ScenarioBuilder {
    name: String,
    description: String,
    arena: Option<Xy>,
    wall_thickness_m: Option<f64>,
    kinds: Vec<KindDraft>,
    rest_stations: Vec<(Xy, f64)>,
    tasks: Vec<TaskDraft>,
    debris: Vec<DebrisDraft>,
    debris_fields: Vec<DebrisFieldSpec>,
    radiation_zones: Vec<(Xy, f64, f64)>,
    duration_s: Option<f64>,
    spec: ScenarioSpec,
}

/// A listed obstacle, its numbers not yet checked.
#[derive(Debug, Clone)]
enum DebrisDraft {
    Rect(DebrisSpec),
    Circle(Xy, f64),
}

impl ScenarioSpec {
    /// A builder for a scenario called `name` (non-empty; names the output folder), every
    /// field at its file default. Set the arena, the kinds, a rest station and the tasks, then
    /// [`ScenarioBuilder::build`]:
    ///
    /// ```
    /// use usar_sim::scenario::{KindDraft, Role, ScenarioSpec, TaskDraft};
    ///
    /// let scenario = ScenarioSpec::builder("mine")
    ///     .arena(40.0, 30.0)
    ///     .kind(
    ///         KindDraft::ground("carrier", Role::Carrier)
    ///             .body_radius_m(0.4)
    ///             .max_speed_m_per_s(1.5)
    ///             .sensing_range_m(3.0)
    ///             .observing_range_m(1.0)
    ///             .carrying_capacity(4)
    ///             .rescuing_resources(1)
    ///             .hp_needs_full(2.0)
    ///             .energy_needs_full(1.5)
    ///             .starts_row((16.0, 2.0), (2.0, 0.0)),
    ///     )
    ///     .rest_station((35.0, 3.0), 2.0)
    ///     .task(
    ///         TaskDraft::new("left", 0)
    ///             .search_area((2.0, 20.0), (12.0, 28.0))
    ///             .goal_m((7.0, 24.0))
    ///             .drop_off((7.0, 8.0), 2.0)
    ///             .rescuee_grid(1.0, 0.5)
    ///             .quota("carrier", 3),
    ///     )
    ///     .build()?;
    /// assert_eq!(scenario.robots().len(), 3);
    /// # Ok::<(), usar_sim::scenario::ScenarioError>(())
    /// ```
    pub fn builder(name: impl Into<String>) -> ScenarioBuilder {
        ScenarioBuilder {
            name: name.into(),
            description: String::new(),
            arena: None,
            wall_thickness_m: None,
            kinds: Vec::new(),
            rest_stations: Vec::new(),
            tasks: Vec::new(),
            debris: Vec::new(),
            debris_fields: Vec::new(),
            radiation_zones: Vec::new(),
            duration_s: None,
            spec: ScenarioSpec {
                name: String::new(),
                description: String::new(),
                // Replaced in `spec()`; `arena` has no default.
                arena: Arena {
                    width_m: super::numbers::Positive::known(1.0),
                    height_m: super::numbers::Positive::known(1.0),
                    wall_thickness_m: super::numbers::Positive::known(0.5),
                },
                kinds: Vec::new(),
                rest_station: RestStationsSpec::Many(Vec::new()),
                tasks: Vec::new(),
                debris: Vec::new(),
                debris_fields: Vec::new(),
                radiation_zones: Vec::new(),
                needs_weights: NeedsWeights::default(),
                mission: MissionParams::default(),
                navigation: NavigationParams::default(),
                collision: CollisionParams::default(),
                sim: SimParams::default(),
                report: ReportSpec::default(),
            },
        }
    }
}

impl ScenarioBuilder {
    /// Free text shown by `usar check`; default empty.
    pub fn description(mut self, text: impl Into<String>) -> Self {
        self.description = text.into();
        self
    }

    /// The field `[0, width_m] x [0, height_m]`, metres, both > 0; required.
    pub fn arena(mut self, width_m: f64, height_m: f64) -> Self {
        self.arena = Some((width_m, height_m));
        self
    }

    /// Boundary wall thickness, metres, > 0; default 0.5.
    pub fn wall_thickness_m(mut self, v: f64) -> Self {
        self.wall_thickness_m = Some(v);
        self
    }

    /// Adds a kind of robot (grouping merge order: the order of the calls); at least one.
    pub fn kind(mut self, kind: KindDraft) -> Self {
        self.kinds.push(kind);
        self
    }

    /// Adds a rest (recharge) station: a disc of `radius_m` (> 0) about `center`; at least
    /// one. One call gives the file's single circle, several a list.
    pub fn rest_station(mut self, center: Xy, radius_m: f64) -> Self {
        self.rest_stations.push((center, radius_m));
        self
    }

    /// Adds a task (output order: the order of the calls); at least one.
    pub fn task(mut self, task: TaskDraft) -> Self {
        self.tasks.push(task);
        self
    }

    /// Adds a listed rectangle of `size` (full width and height, > 0) about `center`, turned
    /// `rotation_deg` counter-clockwise.
    pub fn debris_rect(mut self, center: Xy, size: Xy, rotation_deg: f64) -> Self {
        self.debris.push(DebrisDraft::Rect(DebrisSpec::Rect {
            center_m: [center.0, center.1],
            size_m: [size.0, size.1],
            rotation_deg,
        }));
        self
    }

    /// Adds a listed disc of `radius_m` (> 0) about `center`.
    pub fn debris_circle(mut self, center: Xy, radius_m: f64) -> Self {
        self.debris.push(DebrisDraft::Circle(center, radius_m));
        self
    }

    /// Adds a field of generated debris (the file's `debris_fields` entry).
    pub fn debris_field(mut self, field: DebrisFieldSpec) -> Self {
        self.debris_fields.push(field);
        self
    }

    /// Adds a radiation zone: a disc of `radius_m` (> 0) about `center`, of relative dose
    /// `dose_rate_factor` (> 0; the file's default is 1).
    pub fn radiation_zone(mut self, center: Xy, radius_m: f64, dose_rate_factor: f64) -> Self {
        self.radiation_zones
            .push((center, radius_m, dose_rate_factor));
        self
    }

    /// Trial length, seconds, > 0 (`mission.duration_s`); default 600.
    pub fn duration_s(mut self, v: f64) -> Self {
        self.duration_s = Some(v);
        self
    }

    /// The scenario's seed (`sim.seed`); default 0.
    pub fn seed(mut self, seed: u64) -> Self {
        self.spec.sim.seed = seed;
        self
    }

    /// Weights of the needs vector; default all 1.
    pub fn needs_weights(mut self, w: NeedsWeights) -> Self {
        self.spec.needs_weights = w;
        self
    }

    /// Mission rules; default [`MissionParams::default`] (a later [`Self::duration_s`]
    /// still applies).
    pub fn mission(mut self, m: MissionParams) -> Self {
        self.spec.mission = m;
        self
    }

    /// Path planning; default [`NavigationParams::default`].
    pub fn navigation(mut self, n: NavigationParams) -> Self {
        self.spec.navigation = n;
        self
    }

    /// Collision avoidance; default [`CollisionParams::default`].
    pub fn collision(mut self, c: CollisionParams) -> Self {
        self.spec.collision = c;
        self
    }

    /// Time step, control period and seed; default [`SimParams::default`].
    pub fn sim(mut self, s: SimParams) -> Self {
        self.spec.sim = s;
        self
    }

    /// The `report` section; default none.
    pub fn report(mut self, r: ReportSpec) -> Self {
        self.spec.report = r;
        self
    }

    /// The spec, every number checked but the scenario not validated (e.g. to write it as a
    /// RON file, or to change it further before [`ScenarioSpec::validate`]).
    ///
    /// # Errors
    /// The first number out of range or required field not set, as [`Self::build`].
    pub fn spec(&self) -> Result<ScenarioSpec, ScenarioError> {
        self.checked_spec().map_err(|e| with_origin(e, &self.name))
    }

    /// The validated scenario.
    ///
    /// # Errors
    /// [`ScenarioError::Invalid`] for the first number out of range
    /// (`mine: kinds[0].body_radius_m: expected a finite number > 0, found -0.4`), required
    /// field not set (`mine: arena: missing: ...`), quota naming no kind, or rule of
    /// validation broken; its origin is the scenario's name.
    pub fn build(&self) -> Result<Scenario, ScenarioError> {
        self.spec()?.validate(&self.name)
    }

    fn checked_spec(&self) -> Result<ScenarioSpec, ScenarioError> {
        let mut spec = self.spec.clone();
        spec.name = self.name.clone();
        spec.description = self.description.clone();
        let (width_m, height_m) = self.arena.ok_or_else(|| missing("arena"))?;
        spec.arena.width_m = number_at("arena.width_m", width_m)?;
        spec.arena.height_m = number_at("arena.height_m", height_m)?;
        if let Some(t) = self.wall_thickness_m {
            spec.arena.wall_thickness_m = number_at("arena.wall_thickness_m", t)?;
        }
        let quotas = self.quotas_by_kind()?;
        spec.kinds = (self.kinds.iter().zip(quotas).enumerate())
            .map(|(k, (kind, quota))| kind.to_spec(k, quota))
            .collect::<Result<_, _>>()?;
        spec.rest_station = self.rest_stations()?;
        spec.tasks = (self.tasks.iter().enumerate())
            .map(|(t, task)| task.to_spec(t))
            .collect::<Result<_, _>>()?;
        spec.debris = (self.debris.iter().enumerate())
            .map(|(i, d)| match d {
                DebrisDraft::Rect(r) => Ok(r.clone()),
                DebrisDraft::Circle(center, r) => Ok(DebrisSpec::Circle {
                    center_m: [center.0, center.1],
                    radius_m: number_at(&format!("debris[{i}].radius_m"), *r)?,
                }),
            })
            .collect::<Result<_, ScenarioError>>()?;
        spec.debris_fields = self.debris_fields.clone();
        spec.radiation_zones = (self.radiation_zones.iter().enumerate())
            .map(|(i, &(center, r, dose))| {
                Ok(RadiationZoneSpec {
                    center_m: [center.0, center.1],
                    radius_m: number_at(&format!("radiation_zones[{i}].radius_m"), r)?,
                    dose_rate_factor: number_at(
                        &format!("radiation_zones[{i}].dose_rate_factor"),
                        dose,
                    )?,
                })
            })
            .collect::<Result<_, ScenarioError>>()?;
        if let Some(d) = self.duration_s {
            spec.mission.duration_s = number_at("mission.duration_s", d)?;
        }
        Ok(spec)
    }

    /// The rest stations: one circle for one call, a list for several.
    fn rest_stations(&self) -> Result<RestStationsSpec, ScenarioError> {
        let mut circles = (self.rest_stations.iter().enumerate())
            .map(|(i, &(center, r))| circle(&format!("rest_station[{i}].radius_m"), center, r))
            .collect::<Result<Vec<_>, _>>()?;
        match circles.len() {
            0 => Err(missing("rest_station")),
            1 => Ok(RestStationsSpec::One(circles.remove(0))),
            _ => Ok(RestStationsSpec::Many(circles)),
        }
    }

    /// The tasks' quotas regrouped per kind (the file's form), in kind order.
    ///
    /// # Errors
    /// A quota naming no kind, or a kind twice in one task, at `tasks[t].quota`.
    fn quotas_by_kind(&self) -> Result<Vec<TaskQuotas>, ScenarioError> {
        let mut out = vec![TaskQuotas::default(); self.kinds.len()];
        let names: Vec<&str> = self.kinds.iter().map(KindDraft::name).collect();
        for (t, task) in self.tasks.iter().enumerate() {
            for (kind, robots) in task.quotas() {
                let field = format!("tasks[{t}].quota");
                let Some(k) = names.iter().position(|n| n == kind) else {
                    return Err(field_error(
                        &field,
                        format!(
                            "no kind is called {kind:?}; the kinds are {}{}",
                            names.join(", "),
                            did_you_mean(kind, names.iter().copied())
                        ),
                    ));
                };
                if out[k].0.insert(task.name().to_owned(), *robots).is_some() {
                    return Err(field_error(
                        &field,
                        format!("kind {kind:?} is given twice for task {:?}", task.name()),
                    ));
                }
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{Locomotion, Positive, Role, from_str, parse_spec};

    /// One kind of three carriers and one task: the smallest scenario in code.
    fn tiny() -> ScenarioBuilder {
        tiny_with(carriers(), left())
    }

    /// [`tiny`] with `kind` and `task` for its carriers and its task.
    fn tiny_with(kind: KindDraft, task: TaskDraft) -> ScenarioBuilder {
        ScenarioSpec::builder("tiny")
            .arena(40.0, 30.0)
            .kind(kind)
            .rest_station((35.0, 3.0), 2.0)
            .task(task)
    }

    fn carriers() -> KindDraft {
        KindDraft::ground("carrier", Role::Carrier)
            .body_radius_m(0.4)
            .max_speed_m_per_s(1.5)
            .sensing_range_m(3.0)
            .observing_range_m(1.0)
            .carrying_capacity(4)
            .rescuing_resources(1)
            .hp_needs_full(2.0)
            .energy_needs_full(1.5)
            .starts_row((16.0, 2.0), (2.0, 0.0))
    }

    fn left() -> TaskDraft {
        TaskDraft::new("left", 0)
            .search_area((2.0, 20.0), (12.0, 28.0))
            .goal_m((7.0, 24.0))
            .drop_off((7.0, 8.0), 2.0)
            .rescuee_grid(1.0, 0.5)
            .quota("carrier", 3)
    }

    #[test]
    fn a_built_scenario_takes_the_file_defaults_and_counts_from_quotas() {
        let s = tiny().build().expect("valid");
        assert_eq!(s.name(), "tiny");
        assert_eq!(s.robots().len(), 3);
        assert_eq!(s.kinds()[0].count, 3);
        assert_eq!(s.kinds()[0].locomotion, Locomotion::Ground);
        assert_eq!(*s.mission(), MissionParams::default());
        assert_eq!(*s.sim(), SimParams::default());
        assert_eq!(s.arena().wall_thickness_m, 0.5);
        assert_eq!(*s.report(), ReportSpec::default());
        // The same scenario as its RON.
        let ron = r#"Scenario(
            name: "tiny",
            arena: (width_m: 40.0, height_m: 30.0),
            kinds: [(
                name: "carrier", role: Carrier, locomotion: Ground, count: 3,
                quota: (left: 3), body_radius_m: 0.4, max_speed_m_per_s: 1.5,
                sensing_range_m: 3.0, observing_range_m: 1.0, carrying_capacity: 4,
                rescuing_resources: 1, hp_needs_full: 2.0, energy_needs_full: 1.5,
                starts: Row(first_m: (16.0, 2.0), step_m: (2.0, 0.0)),
            )],
            rest_station: (center_m: (35.0, 3.0), radius_m: 2.0),
            tasks: [(
                name: "left",
                search_area: (min_m: (2.0, 20.0), max_m: (12.0, 28.0)),
                goal_m: (7.0, 24.0),
                drop_off: (center_m: (7.0, 8.0), radius_m: 2.0),
                rescuees: Grid(spacing_m: 1.0, margin_m: 0.5),
            )],
        )"#;
        assert_eq!(from_str(ron, "tiny.ron").expect("valid"), s);
    }

    #[test]
    fn bad_numbers_are_errors_at_build_naming_their_field() {
        let cases = [
            (
                tiny_with(carriers().body_radius_m(-0.4), left()),
                "tiny: kinds[0].body_radius_m: expected a finite number > 0, found -0.4",
            ),
            (
                tiny().arena(40.0, f64::NAN),
                "tiny: arena.height_m: expected a finite number > 0, found NaN",
            ),
            (
                tiny_with(carriers(), left().drop_off((7.0, 8.0), 0.0)),
                "tiny: tasks[0].drop_off.radius_m: expected a finite number > 0, found 0",
            ),
            (
                tiny().rest_station((5.0, 3.0), -1.0),
                "tiny: rest_station[1].radius_m: expected a finite number > 0, found -1",
            ),
            (
                tiny().radiation_zone((20.0, 15.0), 3.0, 0.0),
                "tiny: radiation_zones[0].dose_rate_factor: expected a finite number > 0, \
                 found 0",
            ),
            (
                tiny().duration_s(-600.0),
                "tiny: mission.duration_s: expected a finite number > 0, found -600",
            ),
            (
                tiny().kind(KindDraft::aerial("drone", Role::Observer)),
                "tiny: kinds[1].starts: missing: this field has no default and was not set",
            ),
            (
                tiny_with(carriers(), left().quota("carier", 1)),
                "tiny: tasks[0].quota: no kind is called \"carier\"; the kinds are carrier; \
                 did you mean `carrier`?",
            ),
        ];
        for (builder, want) in cases {
            let err = builder.build().expect_err(want);
            assert_eq!(err.to_string(), want);
            assert_eq!(err.line_col(), None);
        }
        let no_arena = ScenarioSpec::builder("x").kind(carriers()).task(left());
        assert_eq!(
            no_arena.build().expect_err("no arena").field(),
            Some("arena")
        );
    }

    #[test]
    fn the_rules_of_the_file_are_checked_at_build() {
        // Four carriers for a quota of three: the file's rule, at the file's field.
        let err = tiny_with(carriers().count(4), left())
            .build()
            .expect_err("quota below the count");
        assert_eq!(err.origin(), "tiny");
        assert_eq!(err.field(), Some("kinds[0].quota"), "{err}");
        assert_eq!(err.line_col(), None);
    }

    #[test]
    fn to_spec_validates_back_to_an_equal_scenario() {
        for s in [
            tiny().build().expect("valid"),
            crate::scenario::load(paper_path()).expect("paper.ron"),
        ] {
            let back = s.to_spec().validate("again").expect("valid");
            assert_eq!(back, s);
            assert_eq!(back.spec(), s.spec());
            assert_eq!(s.spec(), &s.to_spec());
            // Serialised (the scenario hash), it is the validated parts only, as before the
            // spec was kept inside.
            let json = serde_json::to_value(&s).expect("JSON");
            let mut keys: Vec<&str> = json
                .as_object()
                .expect("an object")
                .keys()
                .map(String::as_str)
                .collect();
            keys.sort_unstable();
            let mut want = [
                "name",
                "description",
                "arena",
                "kinds",
                "robots",
                "rest_stations",
                "tasks",
                "debris",
                "radiation_zones",
                "needs_weights",
                "mission",
                "navigation",
                "collision",
                "sim",
            ];
            want.sort_unstable();
            assert_eq!(keys, want);
        }
    }

    #[test]
    fn an_edit_is_validated_again_and_an_invalid_one_is_an_error() {
        let paper = crate::scenario::load(paper_path()).expect("paper.ron");
        // Count 7 with quotas of 4 + 3 is fine; quotas of 4 + 3 for 6 carriers are not.
        let seven = paper
            .edit(|s| {
                s.kinds[0].count = 7;
                s.kinds[0].quota.0.insert("hard".into(), 4);
            })
            .expect("valid");
        assert_eq!(seven.robots().len(), 13);
        let err = paper
            .edit(|s| {
                s.kinds[0].quota.0.insert("hard".into(), 4);
            })
            .expect_err("quotas exceed the count");
        assert_eq!(err.field(), Some("kinds[0].quota"));
        assert!(err.to_string().starts_with("paper (edited): "), "{err}");
        // A number out of range cannot be written into the spec; given as a plain number
        // it is an error naming the field (tests/tests/integration/scenario_api.rs: a negative speed).
        let err = paper
            .edit(|s| {
                s.kinds[1].sensing_range_m = number_at("kinds[1].sensing_range_m", f64::NAN)?;
                s.kinds[1].count = 0;
                Ok(())
            })
            .expect_err("NaN range");
        assert_eq!(err.field(), Some("kinds[1].sensing_range_m"));
        assert_eq!(err.origin(), "paper (edited)");
        // The scenario edited is unchanged.
        assert_eq!(paper.kinds()[0].count, 6);
        let fast = paper
            .edit(|s| s.kinds[0].max_speed_m_per_s = Positive::new(3.0).expect("> 0"))
            .expect("valid");
        assert_eq!(fast.kinds()[0].max_speed_m_per_s, 3.0);
    }

    #[test]
    fn the_report_section_round_trips_and_rejects_unknown_fields() {
        let paper = crate::scenario::load(paper_path()).expect("paper.ron");
        let want = ReportSpec {
            targets: Some("paper-targets.ron".into()),
            claims: Some("paper-claims.ron".into()),
        };
        assert_eq!(*paper.report(), want);
        // RON written from the spec reads back to an equal spec.
        let text = ron::to_string(paper.spec()).expect("RON");
        assert!(text.contains(r#"report:(targets:"paper-targets.ron",claims:"paper-claims.ron")"#));
        assert_eq!(
            parse_spec(&text, "back.ron").expect("parses"),
            *paper.spec()
        );
        // The report changes no trial: the scenario is equal without it, its spec is not.
        let plain = paper
            .edit(|s| s.report = ReportSpec::default())
            .expect("valid");
        assert_eq!(plain, paper);
        assert_ne!(plain.spec(), paper.spec());
        let src = tiny_ron_with(r#"report: (targets: Some("t.ron"))"#);
        let s = from_str(&src, "t.ron").expect("Some(...) is read too");
        assert_eq!(s.report().targets.as_deref(), Some("t.ron"));
        assert_eq!(s.report().claims, None);
        let err = from_str(&tiny_ron_with("report: (claim: true)"), "t.ron").expect_err("typo");
        assert_eq!(err.field(), Some("report.claim"), "{err}");
        assert!(err.to_string().contains("did you mean `claims`?"), "{err}");
        // The former boolean: `false` is none, `true` names the file that holds the claims.
        let s = from_str(&tiny_ron_with("report: (claims: false)"), "t.ron").expect("false");
        assert_eq!(s.report().claims, None);
        // `true` checked the paper's claims: now the file that holds them, next to paper.ron
        // (the scenario files written before, such as docs/calibration/*/calibrated.ron, load).
        let s = from_str(&tiny_ron_with("report: (claims: true)"), "t.ron").expect("true");
        assert_eq!(s.report().claims.as_deref(), Some("paper-claims.ron"));
        // Anything else is refused naming what the field takes, not serde's enum.
        for bad in ["5", "[\"a\"]", "(x: 1)"] {
            let err = from_str(&tiny_ron_with(&format!("report: (claims: {bad})")), "t.ron")
                .expect_err(bad);
            assert_eq!(err.field(), Some("report.claims"), "{err}");
            let text = err.to_string();
            assert!(text.contains("a claims file's path"), "{bad}: {text}");
            assert!(
                !text.contains("untagged") && !text.contains("PathOrBool"),
                "{text}"
            );
        }
    }

    /// The RON of [`tiny`] with `extra` as its last field.
    fn tiny_ron_with(extra: &str) -> String {
        let spec = tiny().spec().expect("valid numbers");
        let text = ron::to_string(&spec).expect("RON");
        let cut = text.rfind(",report:").expect("a report field");
        format!("{},{extra})", &text[..cut])
    }

    fn paper_path() -> String {
        format!("{}/../../scenarios/paper.ron", env!("CARGO_MANIFEST_DIR"))
    }
}
