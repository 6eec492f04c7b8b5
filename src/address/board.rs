//! OpenPLC boards: how many digital inputs and outputs each wires, so that
//! a program for one uses only addresses the board has.
//!
//! OpenPLC maps digital input `i` of a board to `%IX(i/8).(i%8)` and output
//! `i` to `%QX(i/8).(i%8)` (`bool_input[i/8][i%8]` in every hardware layer),
//! so a board with 14 inputs has `%IX0.0` … `%IX1.5`. The counts come from
//! OpenPLC's own sources: the Runtime's hardware layer for the Raspberry Pi
//! (`webserver/core/hardware_layers/raspberrypi.cpp`, `MAX_INPUT` and
//! `MAX_OUTPUT`) and the Editor's board list for the microcontrollers
//! (`editor/arduino/examples/Baremetal/hals.json`, `default_din` and
//! `default_dout`).

/// One board's digital I/O.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Board {
    /// As `--board` and the SETTINGS sheet name it.
    pub name: &'static str,
    /// As OpenPLC names it.
    pub label: &'static str,
    pub inputs: u32,
    pub outputs: u32,
}

const fn board(name: &'static str, label: &'static str, inputs: u32, outputs: u32) -> Board {
    Board {
        name,
        label,
        inputs,
        outputs,
    }
}

/// Every board steptable knows, as OpenPLC ships them.
pub const BOARDS: [Board; 13] = [
    board("rpi", "Raspberry Pi", 14, 11),
    board("uno", "Arduino Uno", 5, 4),
    board("leonardo", "Arduino Leonardo", 5, 4),
    board("micro", "Arduino Micro", 5, 4),
    board("nano-every", "Arduino Nano Every", 5, 6),
    board("mega", "Arduino Mega", 24, 24),
    board("due", "Arduino Due", 24, 24),
    board("mkr", "Arduino MKR (Zero, WiFi)", 6, 6),
    board("esp32", "ESP32", 9, 10),
    board("esp8266", "ESP8266 D1 mini", 4, 4),
    board("pico", "Raspberry Pi Pico", 8, 8),
    board("controllino-mini", "CONTROLLINO MINI", 6, 6),
    board("controllino-mega", "CONTROLLINO MEGA", 16, 24),
];

impl Board {
    /// The board's last address of an area, in IEC notation (`%IX1.5`).
    pub fn last(self, input: bool) -> String {
        let (prefix, count) = if input {
            ("%IX", self.inputs)
        } else {
            ("%QX", self.outputs)
        };
        let last = count - 1;
        format!("{prefix}{}.{}", last / 8, last % 8)
    }

    /// What the board wires of an area, for messages: `14 inputs (%IX0.0 … %IX1.5)`.
    pub fn span(self, input: bool) -> String {
        let (count, noun, first) = if input {
            (self.inputs, "inputs", "%IX0.0")
        } else {
            (self.outputs, "outputs", "%QX0.0")
        };
        format!("{count} {noun} ({first} … {})", self.last(input))
    }
}

impl std::str::FromStr for Board {
    type Err = String;

    /// A board's name, in any case.
    fn from_str(text: &str) -> Result<Self, String> {
        let lower = text.trim().to_ascii_lowercase();
        BOARDS.into_iter().find(|b| b.name == lower).ok_or_else(|| {
            let names: Vec<&str> = BOARDS.iter().map(|b| b.name).collect();
            format!(
                "\"{text}\" is not an OpenPLC board steptable knows (expected {})",
                names.join(", ")
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_raspberry_pi_wires_what_its_hardware_layer_reads() {
        let rpi: Board = "RPi".parse().unwrap();
        assert_eq!(rpi.span(true), "14 inputs (%IX0.0 … %IX1.5)");
        assert_eq!(rpi.span(false), "11 outputs (%QX0.0 … %QX1.2)");
        let uno: Board = "uno".parse().unwrap();
        assert_eq!(uno.last(true), "%IX0.4");
        assert_eq!(uno.last(false), "%QX0.3");
    }

    #[test]
    fn every_board_parses_from_its_name_and_no_other() {
        for board in BOARDS {
            assert_eq!(board.name.to_uppercase().parse::<Board>(), Ok(board));
        }
        let err = "beaglebone".parse::<Board>().unwrap_err();
        assert!(err.contains("rpi, uno"), "{err}");
    }
}
