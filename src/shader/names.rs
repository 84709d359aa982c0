//! Names in the written code. naga's back ends give every identifier of a module one global
//! namespace, in the order types, entry points (with their arguments), functions (with their
//! arguments and locals, in arena order), globals, constants: a callee's parameter `wi` would
//! make the top-level function's parameter `wi_1`, and a callee's parameter `uniforms` would
//! rename the constant `uniforms`. Callees come before their callers, so the public names --
//! the top-level functions' arguments, the constants, textures, types and functions -- are
//! protected here: in the IR, other functions' arguments and locals of those names get a
//! suffix (`wi_in`, `k_var`); in the written text, a later top-level function's arguments
//! get their own names back where naga had to number them (`wi_1` -> `wi`), and so do every
//! function's arguments and the values the Rust code labelled ([`crate::real::Real::label`]:
//! `cos_phi_2` -> `cos_phi`).

use super::body::Top;
use super::write::Lang;
use naga::Module;
use std::collections::HashSet;

/// The names the entry point and its buffers use.
const ENTRY_NAMES: [&str; 6] = [
    "hair_main",
    "id",
    "hair_queries",
    "hair_values",
    "row",
    "first",
];

/// Renames the arguments and locals of the functions that are not top-level functions where
/// they take a public name (see the [module docs](self)).
pub(super) fn protect_public_names(module: &mut Module, tops: &[Top]) {
    let mut reserved: HashSet<String> = ENTRY_NAMES.iter().map(|s| s.to_string()).collect();
    reserved.extend(module.types.iter().filter_map(|(_, t)| t.name.clone()));
    reserved.extend(module.functions.iter().filter_map(|(_, f)| f.name.clone()));
    reserved.extend(
        module
            .global_variables
            .iter()
            .filter_map(|(_, g)| g.name.clone()),
    );
    reserved.extend(module.constants.iter().filter_map(|(_, c)| c.name.clone()));
    for t in tops {
        let f = &module.functions[t.handle];
        reserved.extend(f.arguments.iter().filter_map(|a| a.name.clone()));
        reserved.extend(f.local_variables.iter().filter_map(|(_, v)| v.name.clone()));
    }
    let is_top = |h| tops.iter().any(|t| t.handle == h);
    for (h, f) in module.functions.iter_mut() {
        if is_top(h) {
            continue;
        }
        for a in &mut f.arguments {
            rename(&mut a.name, "_in", &reserved);
        }
        for (_, v) in f.local_variables.iter_mut() {
            rename(&mut v.name, "_var", &reserved);
        }
    }
}

fn rename(name: &mut Option<String>, suffix: &str, reserved: &HashSet<String>) {
    if let Some(n) = name {
        while reserved.contains(n.as_str()) {
            n.push_str(suffix);
        }
    }
}

/// Gives each function `(name, wanted names)` -- its arguments and labelled values
/// ([`crate::real::Real::label`]) -- its names back in `text` where
/// the back end numbered them (`wi_1`, `cos_phi_2`), when that is safe: the name does not
/// occur in the function (so nothing it refers to is shadowed, and a name wanted twice is
/// given back once) and the back end wrote it elsewhere as an identifier (so it is no keyword
/// of the language).
pub(super) fn restore_names(text: &str, lang: Lang, functions: &[(String, Vec<String>)]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for (function, arguments) in functions {
        let Some(start) = lines
            .iter()
            .position(|l| super::write::is_definition(l, function, lang))
        else {
            continue;
        };
        let Some(end) = (start..lines.len()).find(|&i| lines[i] == "}") else {
            continue;
        };
        for wanted in arguments {
            let region = lines[start..=end].join("\n");
            if contains_word(&region, wanted) {
                continue;
            }
            let Some(written) = numbered_word(&region, wanted) else {
                continue;
            };
            let elsewhere = lines[..start]
                .iter()
                .chain(&lines[end + 1..])
                .any(|l| contains_word(l, wanted));
            if !elsewhere {
                continue;
            }
            for line in &mut lines[start..=end] {
                *line = replace_word(line, &written, wanted);
            }
        }
    }
    let mut out = lines.join("\n");
    if text.ends_with('\n') {
        out.push('\n');
    }
    out
}

/// The identifiers of `text`, in order, without struct members (`x` of `v.x`: a member is
/// no reference to a variable, so it neither shadows nor is renamed).
fn words(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices() {
        match (is_ident(c), start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                out.push((s, &text[s..i]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, &text[s..]));
    }
    out.retain(|&(s, _)| !text[..s].ends_with('.'));
    out.into_iter()
}

fn contains_word(text: &str, word: &str) -> bool {
    words(text).any(|(_, w)| w == word)
}

/// The first identifier of `text` that is `base` numbered by naga's namer (`base_1`, or
/// `base_` for a name naga had to change otherwise).
fn numbered_word(text: &str, base: &str) -> Option<String> {
    words(text)
        .map(|(_, w)| w)
        .find(|w| {
            w.strip_prefix(base)
                .and_then(|rest| rest.strip_prefix('_'))
                .is_some_and(|n| n.chars().all(|c| c.is_ascii_digit()))
        })
        .map(str::to_string)
}

fn replace_word(line: &str, from: &str, to: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut last = 0;
    for (i, w) in words(line) {
        if w == from {
            out.push_str(&line[last..i]);
            out.push_str(to);
            last = i + w.len();
        }
    }
    out.push_str(&line[last..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbered_arguments_get_their_names_back_where_safe() {
        let text = "fn f(wi: vec3<f32>) -> f32 {\n    return wi.x;\n}\n\n\
                    fn g(wi_1: vec3<f32>, h_2: f32) -> f32 {\n    return wi_1.x + h_2 + f(wi_1);\n}\n";
        let tops = [("g".to_string(), vec!["wi".to_string(), "h".to_string()])];
        let out = restore_names(text, Lang::Wgsl, &tops);
        // `h` is written nowhere else: it might be a keyword, so `h_2` stays.
        assert!(
            out.contains(
                "fn g(wi: vec3<f32>, h_2: f32) -> f32 {\n    return wi.x + h_2 + f(wi);\n}"
            ),
            "{out}"
        );
        assert!(out.starts_with("fn f(wi: vec3<f32>)"), "{out}");
        // A function that refers to something named `wi` keeps `wi_1`.
        let shadowing =
            "var<private> wi: f32;\nfn g(wi_1: f32) -> f32 {\n    return wi_1 + wi;\n}\n";
        let tops = [("g".to_string(), vec!["wi".to_string()])];
        assert_eq!(restore_names(shadowing, Lang::Wgsl, &tops), shadowing);
    }
}
