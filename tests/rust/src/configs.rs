//! Prints `topic hex` per computed config of the asset (gen::asset::configs), and the
//! dictionary's sizes: `commands N topics N`.

fn main() {
    for (topic, bytes) in gen::asset::configs().expect("every config encodes") {
        let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
        println!("{topic} {hex}");
    }
    println!("commands {} topics {}", gen::asset::COMMANDS.len(), gen::asset::TOPICS.len());
}
