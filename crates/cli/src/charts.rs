//! Chart styling shared by the commands' figures.

/// Palette colour of a fit model, the same in every figure: the measured data 0, `gw-dmt` 1,
/// `explicit` 2, `explicit-ensemble` 3, `discrete-nN` 4, 5, 6 for N = 1, 2, 3 (then repeating).
pub fn model_color(model: &str) -> usize {
    match model {
        "gw-dmt" => 1,
        "explicit" => 2,
        "explicit-ensemble" => 3,
        m => match m.strip_prefix("discrete-n").and_then(|n| n.parse::<usize>().ok()) {
            Some(n) => 4 + (n + 2) % 3,
            None => 0,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::model_color;

    #[test]
    fn each_model_has_its_own_colour() {
        let names = ["gw-dmt", "explicit", "explicit-ensemble", "discrete-n1", "discrete-n2", "discrete-n3"];
        let c: Vec<usize> = names.iter().map(|n| model_color(n)).collect();
        for (i, a) in c.iter().enumerate() {
            assert_ne!(*a, 0, "{} shares the data's colour", names[i]);
            for b in &c[i + 1..] {
                assert_ne!(a, b, "{c:?}");
            }
        }
    }
}
