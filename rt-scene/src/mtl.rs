//! `.mtl` text checked and put in the form `tobj` reads, line by line,
//! before `tobj` sees it: colours (`Ka`, `Kd`, `Ks`, `Ke`, `Tf`) may give
//! one number for grey, as the format allows (`tobj` asks for three, and
//! panics on fewer), scalars (`Ns`, `Ni`, `d`, `Tr`) one; every number
//! must parse and be finite. A problem is the line's number and what is
//! wrong.

/// The text with one-number colours spelled as three, or the first
/// problem with its (1-based) line.
pub fn normalise(text: &str) -> Result<String, (usize, String)> {
    let mut out = String::with_capacity(text.len() + 16);
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        let rest: Vec<&str> = words.collect();
        match keyword {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => {
                if matches!(rest.first(), Some(&"spectral") | Some(&"xyz")) {
                    return Err((n, format!("`{keyword} {}` colours are not supported (give r g b)", rest[0])));
                }
                let values = numbers(keyword, &rest).map_err(|p| (n, p))?;
                let rgb = match values[..] {
                    [v] => [v, v, v],
                    [r, g, b] => [r, g, b],
                    _ => {
                        return Err((
                            n,
                            format!("`{keyword}` takes 1 number (grey) or 3 (r g b), not {}", values.len()),
                        ));
                    }
                };
                out.push_str(&format!("{keyword} {} {} {}\n", rgb[0], rgb[1], rgb[2]));
                continue;
            }
            "Ns" | "Ni" | "d" | "Tr" => {
                let values = numbers(keyword, &rest).map_err(|p| (n, p))?;
                if values.len() != 1 {
                    return Err((n, format!("`{keyword}` takes 1 number, not {}", values.len())));
                }
            }
            "newmtl" if rest.is_empty() => return Err((n, "`newmtl` needs a material name".into())),
            // Names after a tab: `tobj` splits these lines at a space.
            "newmtl" => {
                out.push_str(&format!("newmtl {}\n", rest.join(" ")));
                continue;
            }
            _ => {}
        }
        out.push_str(line);
        out.push('\n');
    }
    Ok(out)
}

/// Every word as a finite number.
fn numbers(keyword: &str, words: &[&str]) -> Result<Vec<f32>, String> {
    if words.is_empty() {
        return Err(format!("`{keyword}` needs a number"));
    }
    words
        .iter()
        .map(|w| match w.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(v) => Err(format!("`{keyword}` has {v}, which is not finite")),
            Err(_) => Err(format!("`{keyword}` has `{}`, which is not a number", crate::clip::clip(w))),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::normalise;

    #[test]
    fn a_grey_is_one_number_and_bad_numbers_name_their_line() {
        assert_eq!(normalise("newmtl\tm\nKd 1\nKs 0.1 0.2 0.3\n").unwrap(), "newmtl m\nKd 1 1 1\nKs 0.1 0.2 0.3\n");
        let cases = [
            ("newmtl m\nKd 1 2\n", 2, "`Kd` takes 1 number (grey) or 3 (r g b), not 2"),
            ("Kd inf 0 0\n", 1, "`Kd` has inf, which is not finite"),
            ("\nNs NaN\n", 2, "`Ns` has NaN, which is not finite"),
            ("Ka x\n", 1, "`Ka` has `x`, which is not a number"),
            ("Ke\n", 1, "`Ke` needs a number"),
            ("Kd spectral f.rfl\n", 1, "`Kd spectral` colours are not supported (give r g b)"),
            ("d 1 1\n", 1, "`d` takes 1 number, not 2"),
        ];
        for (text, line, problem) in cases {
            assert_eq!(normalise(text), Err((line, problem.to_string())), "{text:?}");
        }
    }
}
